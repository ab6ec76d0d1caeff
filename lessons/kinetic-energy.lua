-- Kinetic energy of a rigid body (003 "Energy"): T = ½p·v + ½L·ω, the same as ½mv² + ½ωᵀIω and
-- as the sum of ½mᵢvᵢ² over the body's particles; constant while a free body tumbles.

-- Six particles (kg, body-frame offsets from the centre of mass in m); Σ mᵢrᵢ = 0.
local particles = {
  {mass = 1, pos = vec3(0.4, 0, 0)}, {mass = 1, pos = vec3(-0.4, 0, 0)},
  {mass = 2, pos = vec3(0, 0.3, 0.1)}, {mass = 2, pos = vec3(0, -0.3, -0.1)},
  {mass = 1, pos = vec3(0.1, 0.1, -0.3)}, {mass = 1, pos = vec3(-0.1, -0.1, 0.3)},
}
local total_mass = 8
-- Σ mᵢ((rᵢ·rᵢ)E − rᵢ⊗rᵢ) added up by hand (kg·m²).
local I_body = mat3(0.6, -0.02, 0.06,
                    -0.02, 0.56, -0.06,
                    0.06, -0.06, 0.72)

local orientation = quat.axis_angle(vec3(2, -1, 1), 1.1)
local velocity = vec3(1, -2, 0.5)             -- m/s, of the centre of mass
local angular_velocity = vec3(2, 1, -1)       -- rad/s, world frame

local function make_body()
  return body{mass = total_mass, inertia = I_body, position = vec3(1, 2, 3),
              orientation = orientation, velocity = velocity, angular_velocity = angular_velocity}
end

-- Σ ½mᵢ|vᵢ|² with each particle's world velocity vᵢ = v + ω × (R·rᵢ), and Σ (R·rᵢ) × mᵢvᵢ.
local function particle_sums(v, omega, q)
  local energy, momentum = 0, vec3(0, 0, 0)
  for _, p in ipairs(particles) do
    local r = q:rotate(p.pos)
    local v_i = v + omega:cross(r)
    energy = energy + 0.5 * p.mass * v_i:dot(v_i)
    momentum = momentum + r:cross(p.mass * v_i)
  end
  return energy, momentum
end

return lesson{
  id = "kinetic-energy",
  title = "Kinetic energy of a tumbling body",
  source = "003_636de12a6b81385f.txt, \"Energy\"",
  steps = {
    {
      title = "The energy of the particles",
      text = [[
Kinetic energy is the energy a body has because it moves: for a single particle ½mv². A rigid
body is a crowd of particles, and its kinetic energy is theirs added up, each with its own
velocity. When the body both travels and spins, a particle at offset r from the centre of mass
moves with vᵢ = v + ω × r: the centre's velocity plus its share of the spin.

Our body: six particles of 8 kg in all (their tensor, added up by hand, is in the lesson's
file), its centre moving at v = (1, −2, 0.5) m/s, spinning at ω = (2, 1, −1) rad/s, turned
1.1 rad about (2, −1, 1). We add up ½mᵢ|vᵢ|² particle by particle; rigidlab's
b:kinetic_energy() must agree.]],
      formula = "T = Σᵢ ½·mᵢ·|vᵢ|²,   vᵢ = v + ω × rᵢ",
      run = function(ctx)
        local mass, com, I = inertia.points(particles)
        ctx:expect("the particles: mass 8, centre at the origin", {mass, com.x, com.y, com.z},
                   {8, 0, 0, 0})
        ctx:expect("the particles' tensor = the hand sum in the file", I, I_body)
        local b = make_body()
        local rows = {}
        for i, p in ipairs(particles) do
          local r = orientation:rotate(p.pos)
          local v_i = velocity + angular_velocity:cross(r)
          rows[i] = {i, p.mass, string.format("(%.4f, %.4f, %.4f)", v_i.x, v_i.y, v_i.z),
                     0.5 * p.mass * v_i:dot(v_i)}
          ctx:expect("particle " .. i .. ": b:point_velocity = v + ω × r",
                     b:point_velocity(b:to_world(p.pos)), v_i)
        end
        ctx:table({"particle", "m (kg)", "vᵢ (m/s)", "½mᵢvᵢ² (J)"}, rows)
        local energy = particle_sums(velocity, angular_velocity, orientation)
        ctx:show("Σ ½mᵢ|vᵢ|² (J)", energy)
        ctx:show("b:kinetic_energy() (J)", b:kinetic_energy())
        ctx:expect("engine T = sum over the particles", b:kinetic_energy(), energy)
      end,
    },
    {
      title = "Travelling plus spinning: ½mv² + ½ωᵀIω",
      text = [[
Expanding |v + ω × r|² gives three terms: v² for every particle, which adds up to ½mv²; the
spin part |ω × r|², which adds up to ½ωᵀIω with the world-frame tensor; and a cross term
v·(ω × Σmᵢrᵢ), which vanishes because offsets are measured from the centre of mass, where
Σmᵢrᵢ = 0. So a rigid body's energy splits cleanly into the energy of its centre of mass moving
and the energy of spinning about it (König's theorem). The spin part can be worked out in
either frame: ωᵀ·I_world·ω = ω_bodyᵀ·I_body·ω_body, with ω_body = Rᵀω.]],
      formula = "T = ½·m·v² + ½·ωᵀ·I_world·ω,   I_world = R·I_body·Rᵀ",
      run = function(ctx)
        local b = make_body()
        local translation = 0.5 * total_mass * velocity:dot(velocity)
        local omega_body = orientation:conj():rotate(angular_velocity)
        local rotation = 0.5 * omega_body:dot(I_body * omega_body)
        ctx:show("½mv² (J)", translation)
        ctx:expect("½mv² = ½·8·(1 + 4 + 0.25) = 21", translation, 21)
        ctx:show("ω in body axes, Rᵀω (rad/s)", omega_body)
        ctx:show("½ω_bodyᵀ·I_body·ω_body (J)", rotation)
        ctx:expect("spin part in world axes: ½ωᵀ(b:world_inertia())ω",
                   0.5 * angular_velocity:dot(b:world_inertia() * angular_velocity), rotation)
        ctx:expect("engine T = ½mv² + ½ωᵀIω", b:kinetic_energy(), translation + rotation)
      end,
    },
    {
      title = "In momentum form: ½p·v + ½L·ω",
      text = [[
003 writes the same energy with momenta: ½p·v for the travel (p = mv, so that is ½mv²) and
½L·ω for the spin (L = Iω, so that is ½ωᵀIω). The linear half
looks like a trivial rewrite, but the angular half is useful: it shows that the energy is the
projection of L on ω. For a given |L| the spin energy ½LᵀI⁻¹L lies between |L|²/(2I_max) and
|L|²/(2I_min): the extremes come with L along the principal axes of largest and smallest
moment, where ω is parallel to L.

We take p and L from the engine and check L against its definition as a sum over particles,
Σ rᵢ × mᵢvᵢ.

A slip in the same section of 003: the energy balance of a collision is printed as
½m₁v₁² + ½m₂v₂² = ½m₁v₁² + ½m₂v₂² + T_lost, with the same velocities on both sides, which would
force T_lost = 0. The right side should have the velocities after the collision, v₁' and v₂'.]],
      formula = "T = ½·p·v + ½·L·ω,   p = m·v,   L = I·ω",
      run = function(ctx)
        local b = make_body()
        local p, L = b:linear_momentum(), b:angular_momentum()
        local _, L_particles = particle_sums(velocity, angular_velocity, orientation)
        ctx:show("p = b:linear_momentum() (kg·m/s)", p)
        ctx:show("L = b:angular_momentum() (kg·m²/s)", L)
        ctx:expect("p = m·v = 8·(1, −2, 0.5)", p, vec3(8, -16, 4))
        ctx:expect("L = Σ rᵢ × mᵢvᵢ", L, L_particles)
        local T = 0.5 * p:dot(velocity) + 0.5 * L:dot(angular_velocity)
        ctx:show("½p·v (J)", 0.5 * p:dot(velocity))
        ctx:show("½L·ω (J)", 0.5 * L:dot(angular_velocity))
        ctx:show("½p·v + ½L·ω (J)", T)
        local energy = particle_sums(velocity, angular_velocity, orientation)
        ctx:expect("½p·v + ½L·ω = Σ ½mᵢ|vᵢ|²", T, energy)
      end,
    },
    {
      title = "Tumbling freely: ω wanders, T and L stay",
      text = [[
Let the body go, with no gravity and no other forces, and let rigidlab's world integrate its
motion (RK4, steps of 1 ms, for 2 s). Its ω is not a principal axis, so the body tumbles: ω
changes direction and size from moment to moment. Yet with no torque, L stays fixed, and with
no forces doing work, T stays fixed too. ½L·ω being constant while ω itself moves means ω
can only wander in a way that keeps its projection on the fixed L the same.

The integrator is not exact, so the check allows a relative drift of 1e-9 in T and in L over
the 2000 steps; RK4's error per step is of order Δt⁵, far below that.]],
      formula = "no torque: L = const,  T = ½·L·ω = const,  while ω = I_world⁻¹·L changes",
      run = function(ctx)
        local w = world{gravity = vec3(0, 0, 0), integrator = "rk4"}
        local b = w:add(make_body())
        local T0, L0, omega0 = b:kinetic_energy(), b:angular_momentum(), b.angular_velocity
        local rows = {}
        for i = 0, 4 do
          if i > 0 then w:step(0.001, 500) end
          local omega, L = b.angular_velocity, b:angular_momentum()
          rows[#rows + 1] = {string.format("%.1f", w.time),
                             string.format("(%.4f, %.4f, %.4f)", omega.x, omega.y, omega.z),
                             0.5 * L:dot(omega), L:norm()}
        end
        ctx:table({"t (s)", "ω (rad/s)", "½L·ω (J)", "|L| (kg·m²/s)"}, rows)
        ctx:show("ω at the start (rad/s)", omega0)
        ctx:show("ω after 2 s (rad/s)", b.angular_velocity)
        ctx:show("change of ω (rad/s)", (b.angular_velocity - omega0):norm())
        ctx:show("relative change of T", b:kinetic_energy() / T0 - 1)
        ctx:show("relative change of L", (b:angular_momentum() - L0):norm() / L0:norm())
        ctx:expect("T after 2 s = T at the start", b:kinetic_energy() / T0, 1, {rel = 1e-9})
        ctx:expect("L after 2 s = L at the start", b:angular_momentum(), L0,
                   {abs = 1e-9 * L0:norm()})
        ctx:expect("the centre of mass moved 2 s × v", b.position, vec3(1, 2, 3) + 2 * velocity,
                   {abs = 1e-9})
      end,
    },
  },
}
