-- Angular motion in 2D (003 "Angular Dynamics in 2D", "Calculating Torque", "Solving Angular
-- Equations in 2D"): a torque spins up a disc, and the slides' update ω += (τ/I)Δt, θ += ωΔt
-- is stepped by motion.simulate on the angle.

local disc_mass = 4                  -- kg
local disc_radius = 1                -- m
local lever = vec3(0.5, 0, 0)        -- m, where the push acts, from the centre
local push = vec3(0, 2, 0)           -- N
local dt = 0.1                       -- s
local steps = 10                     -- 1 s

-- Izz of a thin disc (a flat cylinder about its axis z): ½·m·R² = 2 kg·m².
local function disc_inertia() return inertia.solid_cylinder(disc_mass, disc_radius, 0.01) end

local function angular_acceleration()
  local torque = lever:cross(push)
  return torque.z / disc_inertia():get(3, 3)
end

local function spin(method)
  local alpha = angular_acceleration()
  return motion.simulate{method = method, accel = function() return alpha end, x0 = 0, v0 = 0,
                         dt = dt, steps = steps}
end

return lesson{
  id = "angular-2d",
  title = "Spinning a disc in 2D: torque, ω and θ",
  source = "003_636de12a6b81385f.txt, \"Angular Dynamics in 2D\", \"Calculating Torque\", " ..
           "\"Solving Angular Equations in 2D\"",
  steps = {
    {
      title = "Every linear quantity has a turning twin",
      text = [[
In a flat world, a body lying in the xy plane can only turn about the z axis, so its
orientation is one number, the angle θ. From there the slides pair each quantity of
straight-line motion with a turning one: position r with angle θ, velocity v with angular
velocity ω = dθ/dt (rad/s), acceleration a with angular acceleration α = dω/dt (rad/s²),
force F with torque τ, and mass m with the moment of inertia I, which says how stubbornly
the body resists being spun up. The law is the same shape too: τ = I·α, like F = m·a.

Our body is a disc of 4 kg and radius 1 m, 0.01 m thick. rigidlab's inertia.solid_cylinder
gives its moment about the axis, ½·m·R² = 2 kg·m² (the thickness does not enter it). We push it with 2 N along y at a point 0.5 m out
along x. The torque is the cross product r × F: only its z component is non-zero in 2D,
1 N·m, and it spins the disc up at α = τ/I = 0.5 rad/s². A push at the centre (r = 0)
would give no torque at all.]],
      formula = "τ = r × F,   τ_z = I·α  ⇒  α = τ_z/I",
      run = function(ctx)
        local I = disc_inertia()
        ctx:show("inertia tensor of the disc (kg·m²)", I)
        ctx:show("I_zz (kg·m²)", I:get(3, 3))
        ctx:expect("I_zz = ½·m·R² = 2", I:get(3, 3), 0.5 * disc_mass * disc_radius ^ 2)
        local torque = lever:cross(push)
        ctx:show("r (m)", lever)
        ctx:show("F (N)", push)
        ctx:show("τ = r × F (N·m)", torque)
        ctx:expect("τ = (0, 0, 0.5 · 2)", torque, vec3(0, 0, 1))
        ctx:show("α = τ_z/I (rad/s²)", angular_acceleration())
        ctx:expect("α = 1/2", angular_acceleration(), 0.5)
        ctx:expect("a push at the centre has no torque", vec3(0, 0, 0):cross(push),
                   vec3(0, 0, 0))
      end,
    },
    {
      title = "Stepping the angle",
      text = [[
The slides solve τ = I·dω/dt and ω = dθ/dt the same way as the linear motion: each step
first adds (τ/I)·Δt to ω, then advances θ by the new ω times Δt. motion.simulate does this
on the angle as its "position" with method = "semi_implicit". Over 1 s in 0.1 s steps the
disc reaches ω = 0.5 rad/s, exactly right since α is constant, but θ comes out 0.275 rad
instead of the exact ½·α·t² = 0.25 rad: the same overshoot as the car of the euler-car
lesson, ½·α·Δt·t.

A slip worth knowing: right after these formulas the slides say "don't actually use
explicit Euler though", implying that is what was shown. It is not: using the new ω to
move θ is semi-implicit Euler, the good variant. True explicit Euler moves θ with the old
ω and gets 0.225 rad, undershooting by as much as semi-implicit overshoots.]],
      formula = "ωₙ = ωₙ₋₁ + (τ/I)·Δt,   θₙ = θₙ₋₁ + ωₙ·Δt   ⇒  θₙ = α·Δt²·n(n+1)/2",
      run = function(ctx)
        local alpha = angular_acceleration()
        local semi, explicit = spin("semi_implicit"), spin("euler")
        local rows, want_theta, want_omega = {}, {}, {}
        for i = 1, steps + 1 do
          local n = i - 1
          want_theta[i] = alpha * dt * dt * n * (n + 1) / 2
          want_omega[i] = alpha * n * dt
          rows[i] = {semi.t[i], semi.v[i], semi.x[i], 0.5 * alpha * semi.t[i] ^ 2, explicit.x[i]}
        end
        ctx:table({"t (s)", "ω (rad/s)", "θ semi-implicit (rad)", "θ exact ½αt²",
                   "θ explicit (rad)"}, rows)
        ctx:expect("ω column = α·t", semi.v, want_omega)
        ctx:expect("θ column = α·Δt²·n(n+1)/2", semi.x, want_theta)
        ctx:expect("ω(1 s) = 0.5 rad/s", semi.v[steps + 1], 0.5)
        ctx:expect("θ(1 s), the slides' update", semi.x[steps + 1], 0.275)
        ctx:expect("θ(1 s), true explicit Euler", explicit.x[steps + 1], 0.225)
        ctx:show("exact θ(1 s) = ½·α·t² (rad)", 0.5 * alpha * 1)
        ctx:expect("overshoot = ½·α·Δt·t", semi.x[steps + 1] - 0.25, 0.5 * alpha * dt * 1)
      end,
    },
    {
      title = "The same disc as a rigid body",
      text = [[
rigidlab's 3D world keeps a body's orientation as a quaternion, not an angle, and updates
it by rotating about ω for each step. For a body turning about one fixed axis that reduces
exactly to the 2D update above, so the disc, as a body in a world with the torque of
1 N·m applied every step, must turn by the same angles: 0.275 rad with the semi-implicit
integrator, 0.225 rad with explicit Euler, both with gyroscopic = "implicit" (the plain
update ω += αΔt). With RK4 it turns the exact 0.25 rad, up to about 3e-10 rad from
integrating the quaternion's components and renormalising; that case is checked to 1e-8.
The world's default rotation update, gyroscopic = "conserving", gives the torque's impulse
in two halves, one before and one after the turn, so the turn uses the mid-step ω: for a
constant torque that is the exact 0.25 rad too.]],
      formula = "θ(1 s): semi-implicit 0.275, explicit 0.225, RK4 and conserving ½·α·t² = 0.25 rad",
      run = function(ctx)
        local want = {semi_implicit = 0.275, euler = 0.225, rk4 = 0.25, conserving = 0.25}
        local rows = {}
        for _, method in ipairs({"semi_implicit", "euler", "rk4", "conserving"}) do
          local w = method == "conserving" and world{gravity = vec3(0, 0, 0)}
                    or world{gravity = vec3(0, 0, 0), integrator = method,
                             gyroscopic = method ~= "rk4" and "implicit" or nil}
          local disc = w:add(body{mass = disc_mass, inertia = disc_inertia()})
          local torque = lever:cross(push)
          w:add_force(function() disc:apply_torque(torque) end)
          w:step(dt, steps)
          local axis, angle = disc.orientation:axis_angle()
          rows[#rows + 1] = {method, disc.angular_velocity.z, angle, tostring(axis)}
          ctx:expect(method .. ": ω(1 s) = (0, 0, 0.5)", disc.angular_velocity,
                     vec3(0, 0, 0.5), 1e-12)
          ctx:expect(method .. ": θ(1 s)", angle, want[method],
                     method == "rk4" and {abs = 1e-8} or 1e-12)
        end
        ctx:table({"integrator", "ω_z (rad/s)", "θ (rad)", "axis"}, rows)
      end,
    },
  },
}
