-- "Linear motion is rotation about a point at infinity" (001 "System Of Particles"): for a
-- particle on a rod about an immovable pivot, the rotational term of the impulse's
-- denominator, (I⁻¹(r×N))×r·N, equals 1/m, so the rotational impulse is the linear one. The
-- lesson checks the claim with the engine, and shows where a radius going to infinity
-- matters and where it does not.

local pivot_mass = 1e30   -- kg: stands in for 001's infinite-mass pivot (see step 1)
local N = vec3(1, 0, 0)   -- the collision normal (separating axis)

-- A particle of mass m at offset r from a pivot, as one rigid body turning about the pivot.
-- The particle alone has no moment about the rod's own line, and rigidlab needs three
-- positive principal moments, so the pivot carries a short axle along z, m/2 at (0, 0, ±|r|):
-- it adds to Ixx and Iyy only (points on the z axis have no moment about z), so
-- Izz = m·(rx² + ry²) is the particle's alone, the only moment a hit in the xy plane sees.
local function rod_inertia(m, r)
  local axle = r:norm()
  local _, _, I = inertia.points{
    {mass = pivot_mass, pos = vec3(0, 0, 0)}, {mass = m, pos = r},
    {mass = m / 2, pos = vec3(0, 0, axle)}, {mass = m / 2, pos = vec3(0, 0, -axle)}}
  return I
end

local function rod_body(m, r, fields)
  fields = fields or {}
  fields.mass, fields.inertia = pivot_mass, rod_inertia(m, r)
  return body(fields)
end

-- The rotational term of 001's denominator for a contact at offset r of body b, from the
-- engine's inverse mass matrix: N·M⁻¹N = 1/M + (I⁻¹(r×N))×r·N (002 "Inverse Mass Matrix").
local function rotational_term(b, r)
  return N:dot(collide.inverse_mass_matrix(b, r, r) * N) - b.inv_mass
end

return lesson{
  id = "rotation-at-infinity",
  title = "Linear motion as rotation about a point at infinity",
  source = "001_8a70f78e0cc79e25.txt, \"System Of Particles\"",
  steps = {
    {
      title = "The rotational term of a particle on a rod is 1/m",
      text = [[
001 ties a particle of mass m to an immovable pivot with a rigid, weightless rod and asks
what a blow along N does when the rod is perpendicular to N. Only the rod's turning about
the pivot can move the particle, so the impulse denominator keeps just the rotational term
(I⁻¹(r×N))×r·N, with I = m·r² the particle's moment about the pivot. Work it out and r²
cancels: (r×N)×r = r²N when r ⟂ N, so the term is 1/m, exactly the linear one. The
document makes r infinite on the way, but the cancellation holds at every radius; what
counts is that r ⟂ N. At an angle θ between r and N only the part of N across the rod
turns it, and the term is sin²θ/m, which is the document's closing remark about r vectors
"close to perpendicular".

To build this in rigidlab, the rod is one body turning about its pivot: the pivot is a
point of 1e30 kg (rigidlab's static bodies cannot turn at all, and 1/M = 1e-30 vanishes
next to 1/m = 1 in double precision) with the particle's tensor from inertia.points.]],
      formula = "(I⁻¹(r×N))×r·N = ((r×N)/(m r²))×r·N = (N/m)·N = 1/m   for r ⟂ N\n" ..
                "(I⁻¹(r×N))×r·N = sin²θ/m   with θ the angle between r and N",
      run = function(ctx)
        local mass = 1
        local rows = {}
        for _, radius in ipairs({0.5, 1, 10, 1000}) do
          local r = vec3(0, -radius, 0)
          local rod = rod_body(mass, r)
          local term = rotational_term(rod, r)
          rows[#rows + 1] = {radius, rod:world_inertia():get(3, 3), term}
          ctx:expect("r = " .. radius .. ": rotational term = 1/m", term, 1 / mass)
        end
        ctx:table({"|r| (m)", "Izz = m r² (kg·m²)", "(I⁻¹(r×N))×r·N (1/kg)"}, rows)
        rows = {}
        for _, degrees in ipairs({90, 60, 30, 10}) do
          local theta = math.rad(degrees)
          local r = vec3(math.cos(theta), -math.sin(theta), 0)   -- at θ from N
          local term = rotational_term(rod_body(mass, r), r)
          rows[#rows + 1] = {degrees, term, math.sin(theta) ^ 2 / mass}
          ctx:expect("θ = " .. degrees .. "°: term = sin²θ/m", term, math.sin(theta) ^ 2 / mass)
        end
        ctx:table({"θ between r and N (°)", "term (1/kg)", "sin²θ/m"}, rows)
      end,
    },
    {
      title = "Two rods collide like two particles",
      text = [[
The numerator matches too: a particle moving at v ⟂ r has angular velocity ω = r×v/|r|²
about the pivot, and ω×r gives back v. So two rods whose particles meet head-on exchange
exactly the impulse of the linear collision-1d lesson. collide.resolve, given the two rods
as bodies turning about their pivots, finds J = 2 N·s for equal 1 kg particles (the
striker stops, the other leaves at 2 m/s) and J = 3.2 N·s against 4 kg (−1.2 and
0.8 m/s), for a rod of 1 m just as for one of 1000 m. (The −2e-30 m/s left on the
striker is the 1e30 kg pivot's share of the impulse.)]],
      formula = "ω = r×v/|r|²,   ω×r = v;   J = −2(vb − va)·N/(1/ma + 1/mb)",
      run = function(ctx)
        local cases = {{mb = 1, J = 2, va = 0, vb = 2}, {mb = 4, J = 3.2, va = -1.2, vb = 0.8}}
        local contact, v = vec3(0, 0, 0), vec3(2, 0, 0)
        local rows = {}
        for _, radius in ipairs({1, 1000}) do
          for _, case in ipairs(cases) do
            local ra, rb = vec3(0, -radius, 0), vec3(0, radius, 0)   -- pivot → particle
            local a = rod_body(1, ra, {position = -ra, angular_velocity = ra:cross(v) / ra:dot(ra)})
            local b = rod_body(case.mb, rb, {position = -rb})
            local spin = a.angular_velocity.z
            local label = "|r| = " .. radius .. ", mb = " .. case.mb .. ": "
            ctx:expect(label .. "ω×r = v", a:point_velocity(contact), v)
            local J = collide.resolve(a, b, {point = contact, normal = N, restitution = 1})
            local va, vb = a:point_velocity(contact), b:point_velocity(contact)
            rows[#rows + 1] = {radius, case.mb, spin, J, va.x, vb.x}
            ctx:expect(label .. "J", J, case.J)
            ctx:expect(label .. "va'", va, vec3(case.va, 0, 0))
            ctx:expect(label .. "vb'", vb, vec3(case.vb, 0, 0))
          end
        end
        ctx:table({"|r| (m)", "mb (kg)", "ωa before (rad/s)", "J (N·s)", "va' (m/s)", "vb' (m/s)"}, rows)
      end,
    },
    {
      title = "When the size of r does matter",
      text = [[
It is tempting to summarise the claim as "the impulse tends to the linear one as
‖r‖ → ∞". For 001's particle it is not a limit but an identity, because I = m·r²
grows exactly as r². For other bodies the limit may not exist at all. A ball of radius
ρ = 0.1 m on the rod adds its own moment (2/5)mρ²: the term is r²/(m(r² + 0.4ρ²)), which
does approach 1/m as r grows, only because the ball's own spin becomes negligible. A free
uniform plank of length L hit square at its end has 1/m + (L/2)²/(mL²/12) ≈ 4/m at any
length (the planks here are 1 kg, 5 cm square in section). And a body of fixed inertia hit ever farther from its centre (a ball on a long
light stick) has a term r²/I that grows without bound: it is spun ever more easily, and
the impulse goes to zero, not to the linear one.]],
      formula = "ball on a rod:    r²/(m(r² + 0.4ρ²)) → 1/m\n" ..
                "plank at its end: 1/m + 3L²/(m(L² + w²)) → 4/m\n" ..
                "fixed inertia:    r²/I → ∞",
      run = function(ctx)
        local m, rho, rows = 1, 0.1, {}
        for _, radius in ipairs({0.2, 1, 10, 1000}) do
          local r = vec3(0, -radius, 0)
          local ball_rod = body{mass = pivot_mass,
                                inertia = rod_inertia(m, r) + inertia.solid_sphere(m, rho)}
          local term = rotational_term(ball_rod, r)
          local want = radius ^ 2 / (m * (radius ^ 2 + 0.4 * rho ^ 2))
          rows[#rows + 1] = {radius, term, want}
          ctx:expect("ball of 0.1 m at r = " .. radius, term, want)
        end
        ctx:table({"|r| (m)", "term (1/kg)", "r²/(m(r² + 0.4ρ²))"}, rows)
        rows = {}
        local width = 0.05
        for _, length in ipairs({0.5, 2, 100}) do
          local plank = body.box{mass = m, size = vec3(width, length, width)}
          local r = vec3(0, -length / 2, 0)
          local denominator = N:dot(collide.inverse_mass_matrix(plank, r, r) * N)
          local want = 1 / m + 3 * length ^ 2 / (m * (length ^ 2 + width ^ 2))
          rows[#rows + 1] = {length, denominator, want}
          ctx:expect("plank of " .. length .. " m: 1/m + term", denominator, want)
        end
        ctx:table({"L (m)", "1/m + term (1/kg)", "1/m + 3L²/(m(L² + w²))"}, rows)
        rows = {}
        local ball = body.sphere{mass = m, radius = rho}
        local I = 0.4 * m * rho ^ 2
        for _, arm in ipairs({0.1, 1, 10}) do
          local r = vec3(0, -arm, 0)
          local term = rotational_term(ball, r)
          rows[#rows + 1] = {arm, term, arm ^ 2 / I}
          ctx:expect("ball on a stick, arm " .. arm .. " m: term = r²/I", term, arm ^ 2 / I)
        end
        ctx:table({"arm |r| (m)", "term (1/kg)", "r²/I"}, rows)
      end,
    },
    {
      title = "What the infinite radius does buy: a straight path",
      text = [[
So where does infinity come in? In the path. After the blow the particle runs along a
circle of radius r about the pivot; having travelled a distance s it has strayed
r(1 − cos(s/r)) ≈ s²/(2r) sideways from the straight line it started on. Let a world move
rods of growing length with the particle at 2 m/s for 0.5 s (s = 1 m): the stray shrinks
like 1/r, and at r = ∞ the rotation would be indistinguishable from straight-line motion.
That is the sense in which 001's linear collision is a rotation about a point at infinity.
(The stray is a difference of two numbers near r, so it is checked to 1e-9 m absolute.)]],
      formula = "position after s: (r sin(s/r), −r cos(s/r)) from the pivot\n" ..
                "sideways stray: r(1 − cos(s/r)) ≈ s²/(2r)",
      run = function(ctx)
        local speed, duration, dt = 2, 0.5, 0.01
        local s = speed * duration
        local rows = {}
        for _, radius in ipairs({1, 10, 100, 1000}) do
          local r = vec3(0, -radius, 0)
          local w = world{gravity = vec3(0, 0, 0)}
          local spin = r:cross(vec3(speed, 0, 0)) / radius ^ 2
          local rod = w:add(rod_body(1, r, {angular_velocity = spin}))
          w:step(dt, math.floor(duration / dt + 0.5))
          local particle = rod:to_world(r)
          local angle = s / radius
          local want = vec3(radius * math.sin(angle), -radius * math.cos(angle), 0)
          local stray = particle.y + radius
          rows[#rows + 1] = {radius, spin.z, particle.x, stray, s ^ 2 / (2 * radius)}
          ctx:expect("r = " .. radius .. ": particle on its circle", particle, want, 1e-12)
          ctx:expect("r = " .. radius .. ": stray r(1 − cos(s/r))", stray,
                     radius * (1 - math.cos(angle)), {abs = 1e-9})
        end
        ctx:table({"r (m)", "ω (rad/s)", "x after 1 m (m)", "sideways stray (m)", "≈ s²/(2r) (m)"},
                  rows)
      end,
    },
  },
}
