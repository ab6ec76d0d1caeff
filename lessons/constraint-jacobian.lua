-- Collision impulses from a constraint (001 Appendix D): C = n·(xb − xa) ≥ 0, its rate
-- dC/dt = J v with the 1×12 Jacobian J = [−n, −ra×n, n, rb×n], the effective mass 1/(J W Jᵀ)
-- (J W Jᵀ = 1/ma + 1/mb in the linear case) and the impulse λ = −J v/(J W Jᵀ), which is
-- Appendix C's impulse without restitution.

-- A 12-vector (va, ωa, vb, ωb) is kept as four vec3 blocks.
local function dot12(x, y)
  local sum = 0
  for i = 1, 4 do sum = sum + x[i]:dot(y[i]) end
  return sum
end

-- (Subtracting from the zero vector keeps zero components +0 when printed.)
local function jacobian(ra, rb, n) return {vec3() - n, vec3() - ra:cross(n), n, rb:cross(n)} end
local function velocities(a, b)
  return {a.velocity, a.angular_velocity, b.velocity, b.angular_velocity}
end

-- Inverse inertia of an axis-aligned box of mass m and size s, from the closed form
-- Ixx = m(h² + d²)/12, ... (000 "Inertia of primitive shapes").
local function box_inverse_inertia(m, s)
  return mat3.diag(12 / (m * (s.y ^ 2 + s.z ^ 2)), 12 / (m * (s.x ^ 2 + s.z ^ 2)),
                   12 / (m * (s.x ^ 2 + s.y ^ 2)))
end

-- W Jᵀ for W = diag(1/ma E, Ia⁻¹, 1/mb E, Ib⁻¹), the inverse of 001's block mass matrix.
local function apply_w(blocks, ma, inverse_ia, mb, inverse_ib)
  return {blocks[1] / ma, inverse_ia * blocks[2], blocks[3] / mb, inverse_ib * blocks[4]}
end

local function show_blocks(ctx, label, blocks)
  local names = {"va part", "ωa part", "vb part", "ωb part"}
  for i = 1, 4 do ctx:show(label .. " " .. names[i], blocks[i]) end
end

-- The boxes of steps 3 and 4: 1 kg and 4 kg (001's masses), touching off-centre.
local size_a, size_b = vec3(1, 0.4, 0.6), vec3(1, 1, 1)
local function box_pair()
  local a = body.box{mass = 1, size = size_a, position = vec3(-0.5, 0.3, 0),
                     velocity = vec3(2, 0, 0), angular_velocity = vec3(0, 0.5, 1)}
  local b = body.box{mass = 4, size = size_b, position = vec3(0.5, -0.2, 0.1),
                     velocity = vec3(0, 0.3, 0), angular_velocity = vec3(-0.4, 0, 0)}
  return a, b, vec3(0, 0.1, -0.2), vec3(1, 0, 0)    -- contact point (m) and normal a → b
end

return lesson{
  id = "constraint-jacobian",
  title = "The contact as a constraint: Jacobian, effective mass, impulse",
  source = "001_8a70f78e0cc79e25.txt, \"Appendix D - Deriving Collision Impulses using " ..
           "Constraint Forces\"",
  steps = {
    {
      title = "The constraint and its Jacobian",
      text = [[
Appendix D looks at a contact as a rule the two bodies must obey: the gap along the normal,
C = n·(xb − xa), may not become negative. What the impulse has to fix is how fast C is
changing. Each contact point moves with its body's v + ω×r, and rearranging the triple
products (n·(ω×r) = ω·(r×n)) separates the geometry from the motion: dC/dt is a row of
twelve numbers, the Jacobian J, times the column of the two bodies' linear and angular
velocities. Each block of J says how much one velocity component opens or closes the gap.

Here two boxes touch at a point off both centres: box a, 1 kg and 1 × 0.4 × 0.6 m, centred
at (−0.5, 0.3, 0) m, moving at (2, 0, 0) m/s and turning at (0, 0.5, 1) rad/s; box b, a 4 kg
cube of 1 m, centred at (0.5, −0.2, 0.1) m, moving at (0, 0.3, 0) m/s and turning at
(−0.4, 0, 0) rad/s. They touch at (0, 0.1, −0.2) m with the normal n = (1, 0, 0) from a to b. The Jacobian's blocks come from the
offsets ra and rb of the contact from each centre of mass, and J v must equal the relative
normal velocity of the two contact points as the engine reports it (b:point_velocity).
(Appendix D drops a subscript on the way: after the rearrangement its second term reads
ω·(rb×n), where ωb, the angular velocity of body b, is meant.)]],
      formula = "dC/dt = n·(vb + ωb×rb − va − ωa×ra)\n" ..
                "      = [−n, −ra×n, n, rb×n]·[va, ωa, vb, ωb] = J v",
      run = function(ctx)
        local a, b, point, n = box_pair()
        local ra, rb = point - a.position, point - b.position
        ctx:show("ra (m)", ra)
        ctx:show("rb (m)", rb)
        local J = jacobian(ra, rb, n)
        show_blocks(ctx, "J", J)
        local Jv = dot12(J, velocities(a, b))
        local relative = (b:point_velocity(point) - a:point_velocity(point)):dot(n)
        ctx:show("J v (m/s)", Jv)
        ctx:show("(vb(p) − va(p))·n from point_velocity (m/s)", relative)
        ctx:expect("J v = relative normal velocity", Jv, relative, 1e-12)
      end,
    },
    {
      title = "Linear case: J W Jᵀ = 1/ma + 1/mb",
      text = [[
How hard is it to change dC/dt? Push along Jᵀ with a unit impulse and the velocities change
by W Jᵀ, where W, the inverse of the block mass matrix, holds 1/m and I⁻¹ for each body;
the gap rate then changes by J W Jᵀ. Appendix D first drops rotation and works in 2D: with
J = [−nx, −ny, nx, ny] and W = diag(1/ma, 1/ma, 1/mb, 1/mb) the product is
(1/ma)(nx² + ny²) + (1/mb)(nx² + ny²) = 1/ma + 1/mb for a unit n. For 001's masses 1 and
4 that is 1.25 kg⁻¹, whatever the direction of n. Appendix D calls J W Jᵀ itself "our
calculated effective mass", but its unit is 1/kg: the effective mass, the mass the contact
feels, is its inverse, 0.8 kg here, and that is what collide.effective_mass returns. For two
balls touching on their line of centres, ra×n = rb×n = 0 and rotation drops out by itself:
we check it with two balls of radius 0.5 m (1 kg and 4 kg) centred at −0.5n and 0.5n, which
touch at the origin.]],
      formula = "J W Jᵀ = m_a⁻¹ n_x² + m_a⁻¹ n_y² + m_b⁻¹ n_x² + m_b⁻¹ n_y² = 1/ma + 1/mb",
      run = function(ctx)
        local rows = {}
        for _, degrees in ipairs({0, 30, 120}) do
          local angle = math.rad(degrees)
          local nx, ny = math.cos(angle), math.sin(angle)
          local J = {-nx, -ny, nx, ny}
          local W = {1 / 1, 1 / 1, 1 / 4, 1 / 4}
          local JWJ = 0
          for i = 1, 4 do JWJ = JWJ + J[i] * W[i] * J[i] end
          local n = vec3(nx, ny, 0)
          local a = body.sphere{mass = 1, radius = 0.5, position = -0.5 * n}
          local b = body.sphere{mass = 4, radius = 0.5, position = 0.5 * n}
          local engine = 1 / collide.effective_mass(a, b, vec3(0, 0, 0), n)
          rows[#rows + 1] = {degrees, a.position, JWJ, engine}
          ctx:expect("n at " .. degrees .. "°: J W Jᵀ by hand = 1.25", JWJ, 1.25)
          ctx:expect("n at " .. degrees .. "°: 1/effective_mass = 1.25", engine, 1.25)
        end
        ctx:table({"n at angle (°)", "a's centre (m)", "J W Jᵀ by hand (1/kg)",
                   "1/collide.effective_mass"}, rows)
      end,
    },
    {
      title = "With rotation: the angular blocks add their share",
      text = [[
Keep the angular blocks and J W Jᵀ gains two terms, (ra×n)·Ia⁻¹(ra×n) for body a and the
same for b: a contact off the centre can also be opened by turning the body, so the contact
feels lighter. Built by hand from the boxes' closed-form inertias, the 12-vector product
must equal the inverse of collide.effective_mass.]],
      formula = "J W Jᵀ = 1/ma + 1/mb + (ra×n)·Ia⁻¹(ra×n) + (rb×n)·Ib⁻¹(rb×n)",
      run = function(ctx)
        local a, b, point, n = box_pair()
        local ra, rb = point - a.position, point - b.position
        local J = jacobian(ra, rb, n)
        local WJ = apply_w(J, 1, box_inverse_inertia(1, size_a), 4,
                           box_inverse_inertia(4, size_b))
        show_blocks(ctx, "W Jᵀ", WJ)
        local JWJ = dot12(J, WJ)
        ctx:show("J W Jᵀ (1/kg)", JWJ)
        ctx:show("linear part 1/ma + 1/mb (1/kg)", 1.25)
        ctx:show("angular part (1/kg)", JWJ - 1.25)
        ctx:show("effective mass 1/(J W Jᵀ) (kg)", 1 / JWJ)
        ctx:expect("1/(J W Jᵀ) = collide.effective_mass", 1 / JWJ,
                   collide.effective_mass(a, b, point, n), 1e-12)
      end,
    },
    {
      title = "The impulse λ = −J v/(J W Jᵀ)",
      text = [[
Ask for the impulse λ along Jᵀ that makes the gap rate zero: J(v + W Jᵀλ) = 0 gives
λ = −J v/(J W Jᵀ). In the linear case that is −(vb − va)·n/(1/ma + 1/mb), Appendix C's
impulse without the factor (1 + e): a perfectly plastic contact. For 001's particle at
2 m/s against the resting 4 kg body, λ = 2/1.25 = 1.6 N·s, half the elastic 3.2 N·s.
For the rotating boxes, collide.resolve with restitution 0 must return the same λ, leave
the gap rate at zero, and conserve the total linear momentum. With restitution e the
appendix multiplies λ by (1 + e), and the bodies separate at e times the approach speed.]],
      formula = "λ = −J v/(J W Jᵀ) = −(vb − va)·n/(1/ma + 1/mb) in the linear case\n" ..
                "with restitution e: (1 + e)·λ",
      run = function(ctx)
        local lambda_linear = -(0 - 2) / (1 / 1 + 1 / 4)
        local J_plastic = collide.impulse_1d(1, 2, 4, 0, 0)
        ctx:show("λ, linear, by hand (N·s)", lambda_linear)
        ctx:show("collide.impulse_1d(1, 2, 4, 0, 0) (N·s)", J_plastic)
        ctx:expect("λ = 1.6", lambda_linear, 1.6)
        ctx:expect("impulse_1d with e = 0 gives λ", J_plastic, 1.6)
        ctx:expect("elastic: (1 + 1)·λ = 3.2", collide.impulse_1d(1, 2, 4, 0, 1), 2 * 1.6)

        local a, b, point, n = box_pair()
        local ra, rb = point - a.position, point - b.position
        local J = jacobian(ra, rb, n)
        local JWJ = dot12(J, apply_w(J, 1, box_inverse_inertia(1, size_a), 4,
                                     box_inverse_inertia(4, size_b)))
        local lambda = -dot12(J, velocities(a, b)) / JWJ
        local momentum = a:linear_momentum() + b:linear_momentum()
        local impulse = collide.resolve(a, b, {point = point, normal = n, restitution = 0})
        ctx:show("boxes: λ = −J v/(J W Jᵀ) (N·s)", lambda)
        ctx:show("boxes: J from collide.resolve (N·s)", impulse)
        ctx:expect("boxes: resolve's impulse = λ", impulse, lambda, 1e-12)
        ctx:expect("boxes: J v = 0 afterwards", dot12(J, velocities(a, b)), 0, {abs = 1e-12})
        ctx:expect("boxes: momentum conserved", a:linear_momentum() + b:linear_momentum(),
                   momentum, 1e-12)
        local a2, b2 = box_pair()
        local approach = dot12(J, velocities(a2, b2))
        local elastic = collide.resolve(a2, b2, {point = point, normal = n, restitution = 0.5})
        ctx:expect("e = 0.5: impulse (1 + e)·λ", elastic, 1.5 * lambda, 1e-12)
        ctx:expect("e = 0.5: J v' = −e·J v", dot12(J, velocities(a2, b2)), -0.5 * approach,
                   1e-12)
      end,
    },
  },
}
