-- Angular velocity from a particle's position and velocity (001, opening section): the scalar
-- ω = ‖v‖/‖r‖, the vector ω⃗ = r × v/‖r‖², and three particles at radius 1, 1.5 and 2 that
-- move at the same speed: different angles, the same arc length.

local speed = math.pi   -- m/s, the document's speed for all three particles
local radii = {1, 1.5, 2}

-- Circular motion at constant speed around the origin: the acceleration is centripetal,
-- a = −(‖v‖²/‖x‖²)·x (magnitude v²/r, pointing at the centre).
local function centripetal(_, x, v) return x * (-v:dot(v) / x:dot(x)) end

-- The angle swept along a trajectory, unwrapped: the sum of the small signed angles between
-- consecutive positions (about +z).
local function swept_angle(positions)
  local angle = 0
  for i = 2, #positions do
    local a, b = positions[i - 1], positions[i]
    angle = angle + math.atan(a:cross(b).z, a:dot(b))
  end
  return angle
end

return lesson{
  id = "angular-velocity",
  title = "Angular velocity: turning a straight-line speed into a rate of turning",
  source = "001_8a70f78e0cc79e25.txt, \"Demystifying Rotational Dynamics in Rigid Bodies\" " ..
           "(the opening section, before \"System Of Particles\")",
  steps = {
    {
      title = "How fast is the angle changing?",
      text = [[
A particle tied to a pivot can only go round. Its speed along the circle is ‖v‖, but how
quickly it TURNS depends on how far out it is: covering π metres takes you half-way
round a circle of radius 1, but only a quarter of the way round a circle of radius 2.
Dividing the speed by the radius, ω = ‖v‖/‖r‖, gives the rate of turning in radians per
second, the same for every point of a spinning body no matter how far out it sits.

In 3D a rate of turning also needs an axis. The cross product r × v points along the axis
(right-hand rule: curl your fingers from r toward v, your thumb gives the axis) and has
length ‖r‖‖v‖ when v is perpendicular to r, so dividing by ‖r‖² leaves exactly ω along the
axis. Here a particle 2 m from the pivot moves at π m/s.]],
      formula = "ω = ‖v‖/‖r‖,   ω⃗ = (r × v)/‖r‖² = ω·N̂   (N̂ the unit axis)",
      run = function(ctx)
        local r = vec3(2, 0, 0)
        local v = vec3(0, speed, 0)
        ctx:show("r (m)", r)
        ctx:show("v (m/s)", v)
        ctx:show("‖v‖/‖r‖ (rad/s)", v:norm() / r:norm())
        local cross = r:cross(v)
        ctx:show("r × v (m²/s)", cross)
        local omega = cross / r:dot(r)
        ctx:show("ω⃗ = r × v/‖r‖² (rad/s)", omega)
        ctx:show("axis N̂", omega:normalized())
        ctx:expect("ω = π/2 rad/s", v:norm() / r:norm(), math.pi / 2)
        ctx:expect("ω⃗ = (0, 0, π/2): counter-clockwise seen from +z", omega,
                   vec3(0, 0, math.pi / 2))
        ctx:expect("ω⃗ × r gives the velocity back", omega:cross(r), v)
      end,
    },
    {
      title = "Only the sideways part of v turns the particle",
      text = [[
The document sets the angle between r and v to 90° to drop the sin θ of the cross product
and promises to return to it. Here is what it does: if the particle also moves along r,
away from the pivot, that part of its motion changes the radius, not the angle. The cross
product ignores it automatically, since r × v only sees the component of v perpendicular
to r. So adding 1 m/s of outward speed leaves ω⃗ unchanged, and ω⃗ × r rebuilds only the
sideways part of the velocity.

(A small notational slip in the document: it writes N = A × B = ‖A‖‖B‖ sin θ N, using N
both for the product and for the unit normal; the right-hand side means ‖A‖‖B‖ sin θ N̂.)]],
      formula = "‖r × v‖ = ‖r‖‖v‖ sin θ,   ω⃗ × r = v⊥",
      run = function(ctx)
        local r = vec3(2, 0, 0)
        local v = vec3(1, speed, 0)
        local omega = r:cross(v) / r:dot(r)
        local sine = r:cross(v):norm() / (r:norm() * v:norm())
        ctx:show("v with an outward part (m/s)", v)
        ctx:show("sin θ between r and v", sine)
        ctx:show("ω⃗ (rad/s)", omega)
        ctx:show("ω⃗ × r (m/s)", omega:cross(r))
        ctx:expect("sin θ = π/√(1 + π²)", sine, math.pi / math.sqrt(1 + math.pi ^ 2))
        ctx:expect("ω⃗ unchanged by the radial speed", omega, vec3(0, 0, math.pi / 2))
        ctx:expect("ω⃗ × r = the perpendicular part (0, π, 0)", omega:cross(r),
                   vec3(0, speed, 0))
      end,
    },
    {
      title = "Three radii, one speed: different angles, equal arcs",
      text = [[
Now three particles go round circles of radius 1, 1.5 and 2, all at the same speed of
π m/s, for one second. rigidlab's motion.simulate flies each of them (RK4, 100 steps of
0.01 s) with only the centripetal acceleration v²/r pulling toward the centre, and we add
up the angle each one sweeps. The inner one gets half-way round (π rad), the outer one
only a quarter (π/2 rad), yet all three have travelled the same distance along their
circles: the arc length L = r·θ is π m for each.

The document phrases this as "each particle is at speed of π radians per second". That
is a slip in units: the shared speed is π metres per second along the path; in radians
per second the three differ (π, 2π/3 and π/2). The simulated angles carry RK4's error of
a few 1e-8 rad, so they are checked to 1e-6.]],
      formula = "θ = (‖v‖/r)·t,   L = r·θ   (r = 2, θ = π/2 ⇒ L = π)",
      run = function(ctx)
        local rows = {}
        for _, radius in ipairs(radii) do
          local trajectory = motion.simulate{method = "rk4", accel = centripetal,
                                             x0 = vec3(radius, 0, 0), v0 = vec3(0, speed, 0),
                                             dt = 0.01, steps = 100}
          local angle = swept_angle(trajectory.x)
          local final_radius = trajectory.x[#trajectory.x]:norm()
          rows[#rows + 1] = {radius, speed / radius, angle, radius * angle, final_radius}
          ctx:expect(string.format("r = %g: θ = π/r", radius), angle, math.pi / radius,
                     {abs = 1e-6})
          ctx:expect(string.format("r = %g: arc L = rθ = π", radius), radius * angle, math.pi,
                     {abs = 1e-6})
          ctx:expect(string.format("r = %g: still on its circle", radius), final_radius, radius,
                     {abs = 1e-6})
        end
        ctx:table({"r (m)", "ω = v/r (rad/s)", "θ after 1 s (rad)", "arc rθ (m)",
                   "final ‖x‖ (m)"}, rows)
      end,
    },
  },
}
