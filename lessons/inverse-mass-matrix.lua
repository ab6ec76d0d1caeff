-- The inverse mass matrix (002 "Inverse Mass Matrix", "Collisions"):
-- M⁻¹ = (1/m)E − r̂₂ I⁻¹ r̂₁ maps an impulse at offset r₁ to the velocity change at offset r₂;
-- solving −(v_cm + ω×r) = M⁻¹ j gives the impulse that stops a contact point dead.

local mass = 2                                   -- kg
local size = vec3(0.4, 0.2, 0.6)                 -- m, box width, height, depth
local orientation = quat.axis_angle(vec3(1, 2, 3), 0.7)
local corner = vec3(-0.2, -0.1, 0.3)             -- m, a bottom corner, body frame
local other_corner = vec3(0.2, 0.1, -0.3)        -- m, the opposite corner, body frame

local function make_box()
  return body.box{mass = mass, size = size, orientation = orientation, position = vec3(0, 1, 0),
                  velocity = vec3(1, -2, 0.5), angular_velocity = vec3(0.3, -1, 2)}
end

-- The box's inverse inertia in world axes from the closed form I₀ = diag(m(h²+d²)/12, ...)
-- (000 "Inertia of primitive shapes") and I⁻¹ = A I₀⁻¹ Aᵀ (002 "Rigid Body Dynamics").
local function inverse_world_inertia()
  local w, h, d = size.x, size.y, size.z
  local inverse_body = mat3.diag(12 / (mass * (h * h + d * d)), 12 / (mass * (w * w + d * d)),
                                 12 / (mass * (w * w + h * h)))
  local A = orientation:to_mat3()
  return A * inverse_body * A:transpose()
end

-- 002's formula written out: (1/m)E − r̂₂ I⁻¹ r̂₁.
local function inverse_mass_by_hand(r1, r2)
  return mat3.identity() * (1 / mass) - r2:skew() * inverse_world_inertia() * r1:skew()
end

-- One pass of a normal-then-friction contact (001 "Collisions", Coulomb's bound μJ), written
-- with the matrix by hand: for a contact at offset r with velocity v against a static ground
-- of upward normal n, restitution 0, returns the contact velocity after the pass and the
-- impulse the pass applied.
local function one_pass_by_hand(r, v, n, friction)
  local K = inverse_mass_by_hand(r, r)
  local J = -v:dot(n) / n:dot(K * n)
  v = v + K * (J * n)
  local sliding = v - v:dot(n) * n
  local t = sliding:normalized()
  local lambda = math.min(friction * math.abs(J), sliding:norm() / t:dot(K * t))
  return v + K * (-lambda * t), J * n - lambda * t
end

return lesson{
  id = "inverse-mass-matrix",
  title = "The inverse mass matrix: push here, see the velocity there",
  source = "002_5497adede943f513.txt, \"Inverse Mass Matrix\", \"Collisions\"",
  steps = {
    {
      title = "A force at one point, an acceleration at another",
      text = [[
Push a particle and it accelerates along the push, by f/m. Push a rigid body at some
offset r₁ from its centre of mass and two things happen: the centre accelerates by f/m,
and the torque r₁×f spins it up by I⁻¹(r₁×f). A point at offset r₂ then feels both, the
second through α×r₂. Writing each cross product as a matrix (r̂ v = r×v), the whole chain
is one 3×3 matrix, the inverse mass matrix M⁻¹ = (1/m)E − r̂₂I⁻¹r̂₁. It works the same
for impulses: an impulse j at r₁ changes the velocity at r₂ by M⁻¹j. Note that the
response is not parallel to the push: a body pushed off-centre partly slides and partly
turns away.

Our body is a 2 kg box of 0.4 × 0.2 × 0.6 m, tilted by 0.7 rad (40.1°) about the axis
(1, 2, 3), with its centre at (0, 1, 0) m, moving at (1, −2, 0.5) m/s and turning at
(0.3, −1, 2) rad/s.

Here is a 2 kg box, tilted, pushed at one bottom corner, watched at the same corner and at
the opposite one. collide.inverse_mass_matrix must match the formula assembled by hand from
the box's closed-form inertia, and a real impulse (b:apply_impulse) must change the
watched corner's velocity (b:point_velocity) by exactly M⁻¹j. Swapping the roles of the
two points transposes the matrix: a push at 1 seen at 2 equals a push at 2 seen at 1.]],
      formula = "M⁻¹ = (1/m)E − r̂₂ I⁻¹ r̂₁,   Δv(r₂) = M⁻¹ j,   r̂ = [r]×",
      run = function(ctx)
        local box = make_box()
        local r1 = orientation:rotate(corner)
        local r2 = orientation:rotate(other_corner)
        ctx:show("r₁ (m, world)", r1)
        ctx:show("r₂ (m, world)", r2)
        local same = collide.inverse_mass_matrix(box, r1, r1)
        local across = collide.inverse_mass_matrix(box, r1, r2)
        ctx:show("M⁻¹(r₁, r₁) (1/kg)", same)
        ctx:show("M⁻¹(r₁, r₂) (1/kg)", across)
        ctx:expect("M⁻¹(r₁, r₁) = (1/m)E − r̂₁I⁻¹r̂₁", same, inverse_mass_by_hand(r1, r1), 1e-12)
        ctx:expect("M⁻¹(r₁, r₂) = (1/m)E − r̂₂I⁻¹r̂₁", across, inverse_mass_by_hand(r1, r2), 1e-12)
        ctx:expect("M⁻¹(r₁, r₁) is symmetric", same, same:transpose(), 1e-12)
        ctx:expect("M⁻¹(r₂, r₁) = M⁻¹(r₁, r₂)ᵀ", collide.inverse_mass_matrix(box, r2, r1),
                   across:transpose(), 1e-12)
        local j = vec3(0.3, 0.5, -0.2)   -- N·s
        local before1 = box:point_velocity(box.position + r1)
        local before2 = box:point_velocity(box.position + r2)
        box:apply_impulse(j, box.position + r1)
        local change1 = box:point_velocity(box.position + r1) - before1
        local change2 = box:point_velocity(box.position + r2) - before2
        ctx:show("impulse j at r₁ (N·s)", j)
        ctx:show("velocity change at r₁ (m/s)", change1)
        ctx:show("velocity change at r₂ (m/s)", change2)
        ctx:expect("Δv(r₁) = M⁻¹(r₁, r₁) j", change1, same * j, 1e-12)
        ctx:expect("Δv(r₂) = M⁻¹(r₁, r₂) j", change2, across * j, 1e-12)
      end,
    },
    {
      title = "Stopping a contact point with one impulse",
      text = [[
002 uses the matrix for a landing: the box hits the ground at its corner, with no bounce
and enough friction that the corner does not slide. So right after the impact the corner's
velocity v_cm + ω×r must be zero, and the impulse that does it solves a 3×3 linear system,
−(v_cm + ω×r) = M⁻¹j. We solve it with mat3:inverse, apply j at the corner, and the corner
stops dead while the box as a whole keeps moving and turning.

The kinetic energy that disappears has a closed form: the impulse works against the corner
velocity as it falls from v to 0, on average v/2, so the loss is ½ vᵀ M v with M the mass
matrix, the inverse of M⁻¹. The impulse points up (j_y > 0), so the ground really pushes
and this contact is a valid one.]],
      formula = "−(v_cm + ω×r) = M⁻¹ j  ⇒  j = −M (v_cm + ω×r);   T_lost = ½ vᵀ M v",
      run = function(ctx)
        local box = make_box()
        local r = orientation:rotate(corner)
        local point = box.position + r
        local v_contact = box:point_velocity(point)
        local inverse_mass = collide.inverse_mass_matrix(box, r, r)
        local mass_matrix = inverse_mass:inverse()
        local j = mass_matrix * (-v_contact)
        ctx:show("v_cm (m/s)", box.velocity)
        ctx:show("ω (rad/s)", box.angular_velocity)
        ctx:show("v_cm + ω×r at the corner (m/s)", v_contact)
        ctx:expect("point_velocity = v_cm + ω×r", v_contact,
                   box.velocity + box.angular_velocity:cross(r), 1e-12)
        ctx:show("M = (M⁻¹)⁻¹ (kg)", mass_matrix)
        ctx:show("j (N·s)", j)
        ctx:say(string.format("j_y = %.4g N·s > 0: the ground pushes up, so the contact is valid.",
                              j.y))
        ctx:expect("j = −M(v_cm + ω×r) with M⁻¹ by hand", j,
                   inverse_mass_by_hand(r, r):inverse() *
                     -(box.velocity + box.angular_velocity:cross(r)),
                   1e-12)
        local v_before, omega_before = box.velocity, box.angular_velocity
        local t_before = box:kinetic_energy()
        box:apply_impulse(j, point)
        ctx:show("corner velocity after (m/s)", box:point_velocity(point))
        ctx:show("v_cm after (m/s)", box.velocity)
        ctx:show("ω after (rad/s)", box.angular_velocity)
        ctx:expect("the corner stops", box:point_velocity(point), vec3(0, 0, 0), {abs = 1e-12})
        ctx:expect("Δv_cm = j/m", box.velocity - v_before, j / mass, 1e-12)
        ctx:expect("Δω = I⁻¹(r×j)", box.angular_velocity - omega_before,
                   inverse_world_inertia() * r:cross(j), 1e-12)
        local lost = t_before - box:kinetic_energy()
        ctx:show("kinetic energy lost (J)", lost)
        ctx:expect("T_lost = ½ vᵀ M v", lost, 0.5 * v_contact:dot(mass_matrix * v_contact), 1e-12)
      end,
    },
    {
      title = "One direction at a time needs many passes",
      text = [[
A simple engine handles a contact one direction at a time: first the normal impulse,
computed with the mass along the normal alone, then a friction impulse along the sliding
direction. Because M⁻¹ couples the directions (its off-diagonal entries), the friction
impulse disturbs the normal velocity it had just fixed: after one pass our corner moves
into the ground again at about 1.1 m/s. Repeating the passes, each adding a small
correction, converges to the same total impulse as the one 3×3 solve above, each pass
cutting the error by a factor of about 1.8 (after 40 passes it is below 1e-10 N·s; checked
to 1e-9). This is the idea behind 000's "Sequential impulses". Friction 100 ensures
Coulomb's limit never clips the friction impulse. collide.resolve does not iterate: it
solves the 3×3 system at once (and only falls back to sliding at μJ when the stopping
impulse lies outside Coulomb's cone), so one call stops the corner.]],
      formula = "pass k: J_k along n, then friction along the sliding direction\n" ..
                "Σ impulses → j",
      run = function(ctx)
        local box = make_box()
        local r = orientation:rotate(corner)
        local v0 = box:point_velocity(box.position + r)
        local j = collide.inverse_mass_matrix(box, r, r):inverse() * (-v0)
        local up = vec3(0, 1, 0)
        local total, rows, v = vec3(0, 0, 0), {}, v0
        for pass = 1, 40 do
          local impulse
          v, impulse = one_pass_by_hand(r, v, up, 100)
          total = total + impulse
          if pass == 1 then
            ctx:show("corner velocity after one pass (m/s)", v)
            ctx:expect("after one pass the corner moves into the ground again", v.y < -1 and 1 or 0, 1)
          end
          if pass == 1 or pass % 10 == 0 then
            rows[#rows + 1] = {pass, v:norm(), (total - j):norm()}
          end
        end
        ctx:table({"passes", "‖corner velocity‖ (m/s)", "‖Σ impulses − j‖ (N·s)"}, rows)
        ctx:show("Σ impulses after 40 passes (N·s)", total)
        ctx:show("j from the 3×3 solve (N·s)", j)
        ctx:expect("40 passes converge to j", total, j, 1e-9)
        local floor = body.box{static = true, size = vec3(10, 1, 10), position = vec3(0, -0.5, 0)}
        local point = box.position + r
        local J, friction = collide.resolve(floor, box, {point = point, normal = up,
                                                         restitution = 0, friction = 100})
        ctx:show("collide.resolve, one call: J·n + friction (N·s)", J * up + friction)
        ctx:expect("one collide.resolve = the 3×3 solve", J * up + friction, j, 1e-12)
        ctx:expect("and the corner stops", box:point_velocity(point), vec3(0, 0, 0), {abs = 1e-12})
      end,
    },
  },
}
