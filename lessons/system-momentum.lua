-- A system of particles moving together (001 "System Of Particles"): four particles of mass 1
-- at velocity 1 have total mass 4 and total momentum 4, exactly like one particle of mass 4.

local corners = {vec3(-0.5, -0.5, 0), vec3(0.5, -0.5, 0), vec3(0.5, 0.5, 0), vec3(-0.5, 0.5, 0)}
local velocity = vec3(1, 0, 0)   -- m/s, the document's velocity
local ball_radius = 0.05         -- m, each particle drawn as a small ball

local function point_masses()
  local list = {}
  for i, corner in ipairs(corners) do list[i] = {mass = 1, pos = corner} end
  return list
end

return lesson{
  id = "system-momentum",
  title = "Four particles, one body: total mass and total momentum",
  source = "001_8a70f78e0cc79e25.txt, \"System Of Particles\"",
  steps = {
    {
      title = "Mass adds up",
      text = [[
Tie four particles of 1 kg together with rigid, weightless rods and you have a body. As far
as pushing it in a straight line goes, the rods change nothing: the masses simply add, so
the body has 4 kg. We place the particles on the corners of a 1 m square, at x, y = ±0.5 m; inertia.points
adds their masses and finds their centre of mass in the middle of the square.]],
      formula = "m_total = Σ mᵢ = 1 + 1 + 1 + 1 = 4",
      run = function(ctx)
        local mass, com = inertia.points(point_masses())
        ctx:show("m_total (kg)", mass)
        ctx:show("centre of mass (m)", com)
        ctx:expect("m_total = 4", mass, 4)
        ctx:expect("centre of the square", com, vec3(0, 0, 0), {abs = 1e-15})
      end,
    },
    {
      title = "Momentum adds up too",
      text = [[
Set all four moving at 1 m/s. Each carries momentum m·v = 1 kg·m/s, and the system carries
the sum, 4 kg·m/s: exactly what a single 4 kg particle moving at 1 m/s carries. We check it
with rigidlab's bodies: a world holding four 1 kg balls (each drawn with a radius of 5 cm,
at the corners of the square) reports its total linear momentum, and a single 4 kg ball
reports its own.]],
      formula = "P_total = Σ mᵢvᵢ = 1·1 + 1·1 + 1·1 + 1·1 = 4",
      run = function(ctx)
        local w = world{gravity = vec3(0, 0, 0)}
        for _, corner in ipairs(corners) do
          w:add(body.sphere{mass = 1, radius = ball_radius, position = corner,
                            velocity = velocity})
        end
        local single = body.sphere{mass = 4, radius = ball_radius, velocity = velocity}
        ctx:show("P of the four particles (kg·m/s)", w:linear_momentum())
        ctx:show("P of one 4 kg particle (kg·m/s)", single:linear_momentum())
        ctx:expect("P_total = (4, 0, 0)", w:linear_momentum(), vec3(4, 0, 0))
        ctx:expect("one particle of mass 4: (4, 0, 0)", single:linear_momentum(), vec3(4, 0, 0))
      end,
    },
    {
      title = "Hit it through the centre: it answers like one particle",
      text = [[
Because mass and momentum add, a blow through the centre of mass affects the tied-together
system just as it would a single 4 kg particle. In 001 a 1 kg particle at 2 m/s strikes
the 4 kg body elastically and hands it an impulse of J = 3.2 N·s (the collision-1d lesson
derives that number). We give that impulse to the four-particle square, made into one
rigid body with inertia.points' mass, centre and tensor, and to a lone 4 kg ball: both
leave at J/m = 0.8 m/s, the document's value, and the square does not start to turn,
since the blow passes through its centre of mass.]],
      formula = "v' = v + J/m_total = 0 + 3.2/4 = 0.8",
      run = function(ctx)
        local mass, com, inertia_com = inertia.points(point_masses())
        ctx:show("inertia tensor of the square about its centre (kg·m²)", inertia_com)
        local square = body{mass = mass, inertia = inertia_com, position = com}
        local single = body.sphere{mass = 4, radius = ball_radius}
        local impulse = vec3(3.2, 0, 0)   -- N·s, 001's J for masses 1 and 4
        square:apply_impulse(impulse, com)
        single:apply_impulse(impulse)
        ctx:show("square: v' (m/s)", square.velocity)
        ctx:show("square: ω' (rad/s)", square.angular_velocity)
        ctx:show("single particle: v' (m/s)", single.velocity)
        ctx:expect("square: v' = 0.8", square.velocity, vec3(0.8, 0, 0), 1e-12)
        ctx:expect("square: no rotation", square.angular_velocity, vec3(0, 0, 0), {abs = 1e-12})
        ctx:expect("single particle: v' = 0.8", single.velocity, vec3(0.8, 0, 0), 1e-12)
      end,
    },
  },
}
