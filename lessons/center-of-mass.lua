-- The centre of mass (000 "Center of mass", 001 "System Of Particles", 004 "Center of Mass"):
-- the mass-weighted average position, its velocity P/m, and the one point where a push
-- causes no turning.

-- Three particles in 3D for the velocity and moment steps.
local particles = {
  {mass = 1, pos = vec3(0, 0, 0), velocity = vec3(2, 0, 0)},
  {mass = 2, pos = vec3(3, 0, 0), velocity = vec3(0, 1, 0)},
  {mass = 3, pos = vec3(1, 2, 1), velocity = vec3(0, 0, -1)},
}

-- Two point masses on the x axis, through inertia.points; prints and returns mass and COM.
local function pair(ctx, m1, x1, m2, x2)
  local mass, com = inertia.points{{mass = m1, pos = vec3(x1, 0, 0)},
                                   {mass = m2, pos = vec3(x2, 0, 0)}}
  ctx:show("total mass (kg)", mass)
  ctx:show("COM (m)", com)
  return mass, com
end

-- The particles as inertia.points wants them: {mass =, pos =} only.
local function point_masses()
  local list = {}
  for i, p in ipairs(particles) do list[i] = {mass = p.mass, pos = p.pos} end
  return list
end

-- The same particles moved on by their velocities for dt seconds.
local function advanced(dt)
  local moved = {}
  for i, p in ipairs(particles) do moved[i] = {mass = p.mass, pos = p.pos + p.velocity * dt} end
  return moved
end

-- The particles as one rigid body: mass, COM and inertia tensor from inertia.points.
local function rigid_body()
  local mass, com, inertia_com = inertia.points(point_masses())
  return body{mass = mass, inertia = inertia_com, position = com}, com
end

return lesson{
  id = "center-of-mass",
  title = "The centre of mass: balance point, average motion, no-turning point",
  source = "000_3bd95e59483beea1.txt, \"Center of mass\"; 001_8a70f78e0cc79e25.txt, " ..
           "\"System Of Particles\"; 004_8f5d2bfd6f0c2787.txt, \"Center of Mass\"",
  steps = {
    {
      title = "Two particles on a line",
      text = [[
The centre of mass is where a body would balance on a pin: the average of its particles'
positions, each weighted by its mass. For two particles on a line it is
x = (m₁x₁ + m₂x₂)/(m₁ + m₂), which sits on the segment between them, closer to the heavier
one, and divides it in the inverse ratio of the masses. Put 3 kg at x = 0 and 1 kg at
x = 4 m: the balance point is at 1 m, three times closer to the 3 kg particle.
rigidlab's inertia.points computes the total mass and this weighted average for any list
of point masses.]],
      formula = "x_com = (m₁x₁ + m₂x₂)/(m₁ + m₂),   in general  COM = (1/m)·Σ mᵢ pᵢ",
      run = function(ctx)
        local mass, com = pair(ctx, 3, 0, 1, 4)
        ctx:expect("m = 3 + 1", mass, 4)
        ctx:expect("x_com = (3·0 + 1·4)/(3 + 1) = 1", com, vec3((3 * 0 + 1 * 4) / (3 + 1), 0, 0))
      end,
    },
    {
      title = "A 1000 : 1 pair",
      text = [[
When one mass dwarfs the other the balance point practically sits inside the heavy one.
A 1000 kg mass at x = 0 and a 1 kg mass at x = 1.001 m balance at x = 1.001/1001 = 1 mm
from the heavy mass. This is why, for the Earth and a thrown ball, we can treat the Earth
as fixed: their common centre of mass is, for all purposes, the Earth's own.]],
      formula = "x_com = (1000·0 + 1·1.001)/(1000 + 1) = 0.001 m",
      run = function(ctx)
        local _, com = pair(ctx, 1000, 0, 1, 1.001)
        ctx:show("distance to the heavy mass (m)", com.x)
        ctx:show("distance to the light mass (m)", 1.001 - com.x)
        ctx:expect("x_com = 1.001/1001 = 0.001 m", com, vec3(0.001, 0, 0), {abs = 1e-15})
        ctx:expect("distances in the ratio 1 : 1000", (1.001 - com.x) / com.x, 1000, 1e-12)
      end,
    },
    {
      title = "The centre of mass moves with the average velocity",
      text = [[
Differentiate the weighted average and you get the weighted average of the velocities:
v_com = Σ mᵢvᵢ / Σ mᵢ, which is the total momentum divided by the total mass. So the whole
system of particles, however its parts move, carries its momentum as if it were one
particle of the total mass sitting at the centre of mass (001, "System Of Particles").

Three particles (1, 2 and 3 kg) fly off in different directions. We ask inertia.points for
their centre of mass now and 0.1 s later; the displacement divided by 0.1 s is exactly
P/m, since every particle moves in a straight line and the average of straight-line
motions is a straight-line motion.]],
      formula = "v_com = d/dt x_com = Σ mᵢvᵢ / Σ mᵢ = P_total / m_total",
      run = function(ctx)
        local dt = 0.1
        local mass, com_now = inertia.points(point_masses())
        local _, com_later = inertia.points(advanced(dt))
        local momentum = vec3(0, 0, 0)
        for _, p in ipairs(particles) do momentum = momentum + p.velocity * p.mass end
        ctx:show("COM now (m)", com_now)
        ctx:show("COM 0.1 s later (m)", com_later)
        ctx:show("P_total = Σ mᵢvᵢ (kg·m/s)", momentum)
        ctx:show("P/m (m/s)", momentum / mass)
        local velocity = (com_later - com_now) / dt
        ctx:show("COM displacement / Δt (m/s)", velocity)
        ctx:expect("COM now = (1·(0,0,0) + 2·(3,0,0) + 3·(1,2,1))/6", com_now,
                   vec3(9 / 6, 6 / 6, 3 / 6), 1e-12)
        ctx:expect("v_com = P/m = (2, 2, −3)/6", velocity, vec3(2 / 6, 2 / 6, -3 / 6), 1e-12)
      end,
    },
    {
      title = "Push through the centre of mass and nothing turns",
      text = [[
004 derives the centre of mass from a question: at which point can you push a free body so
that it only slides, without starting to turn? If the push F makes every particle
accelerate alike, particle i must receive the share (mᵢ/m)·F, and the moments of those
shares about the point r must cancel: Σ(rᵢ − r) × (mᵢ/m)F = (Σ(mᵢ/m)(rᵢ − r)) × F = 0 for
every F. That forces r to be the mass-weighted average of the rᵢ. Below, the moment of the
shares vanishes about the COM and not about the origin.

Then a rigid body built from the three particles (inertia.points gives its mass, COM and
inertia tensor) gets a sharp push, an impulse of 2 N·s: through the COM it slides off at
2/6 m/s without turning; the same impulse 1 m to the side also sets it spinning, at
ω = I⁻¹(r × J).]],
      formula = "Σ(rᵢ − r) × (mᵢ/m)·F = 0 for all F  ⇔  r = Σ(mᵢ/m)·rᵢ\n" ..
                "impulse J at offset r from the COM:  Δv = J/m,  Δω = I⁻¹(r × J)",
      run = function(ctx)
        local force = vec3(0, 0, 5)
        local mass, com, inertia_com = inertia.points(point_masses())
        local function moment_of_shares(point)
          local moment = vec3(0, 0, 0)
          for _, p in ipairs(particles) do
            moment = moment + (p.pos - point):cross(force * (p.mass / mass))
          end
          return moment
        end
        ctx:show("F (N)", force)
        ctx:show("moment of the shares about the COM (N·m)", moment_of_shares(com))
        ctx:show("... about the origin (N·m)", moment_of_shares(vec3(0, 0, 0)))
        ctx:expect("no moment about the COM", moment_of_shares(com), vec3(0, 0, 0),
                   {abs = 1e-12})
        ctx:expect("about the origin: COM × F", moment_of_shares(vec3(0, 0, 0)),
                   com:cross(force), 1e-12)

        local impulse = vec3(0, 2, 0)
        local centred = rigid_body()
        centred:apply_impulse(impulse, com)
        ctx:show("through the COM: v (m/s)", centred.velocity)
        ctx:show("through the COM: ω (rad/s)", centred.angular_velocity)
        ctx:expect("v = J/m", centred.velocity, impulse / mass, 1e-12)
        ctx:expect("ω = 0", centred.angular_velocity, vec3(0, 0, 0), {abs = 1e-12})

        local offset = vec3(1, 0, 0)
        local off_centre = rigid_body()
        off_centre:apply_impulse(impulse, com + offset)
        ctx:show("1 m to the side: v (m/s)", off_centre.velocity)
        ctx:show("1 m to the side: ω (rad/s)", off_centre.angular_velocity)
        ctx:expect("v = J/m still", off_centre.velocity, impulse / mass, 1e-12)
        -- The tensor about the COM (1.5, 1, 0.5) by hand, Σ mᵢ((rᵢ·rᵢ)E − rᵢ⊗rᵢ) with rᵢ the
        -- offsets (−1.5, −1, −0.5), (1.5, −1, −0.5), (−0.5, 1, 0.5):
        local by_hand = mat3{{7.5, 3, 1.5}, {3, 9, -3}, {1.5, -3, 13.5}}
        ctx:show("I about the COM (kg·m²)", inertia_com)
        ctx:expect("I = Σ mᵢ((rᵢ·rᵢ)E − rᵢ⊗rᵢ), by hand", inertia_com, by_hand, 1e-12)
        ctx:expect("ω = I⁻¹(r × J) = (−1/15, 2/25, 13/75)", off_centre.angular_velocity,
                   vec3(-1 / 15, 2 / 25, 13 / 75), 1e-12)
        ctx:show("angular momentum about the COM (kg·m²/s)", off_centre:angular_momentum())
        ctx:expect("L = r × J = (1, 0, 0) × (0, 2, 0)", off_centre:angular_momentum(),
                   vec3(0, 0, 2), 1e-12)
      end,
    },
  },
}
