-- One double pendulum two ways (000 "Coordinate simulation", "Sequential impulses"): two balls
-- on hinge joints in a world (full coordinates: 12 numbers held together by impulses) and the
-- same two links as an articulation (reduced coordinates: two angles). The energy of each over
-- time, the joints' drift in the one and its absence in the other, and how the two runs part
-- (the motion is chaotic: any difference grows exponentially).

local L = 1                    -- m, each rod
local mass = 1                 -- kg, each ball
local radius = 0.05            -- m, each ball: a small solid sphere
local g = 9.80665              -- m/s², standard gravity
local theta1, theta2 = 120, -30   -- degrees from the downward vertical, each rod's own angle
local high1, high2 = 150, 150     -- degrees: the release of step 3, nearly upside down
local dt = 0.001               -- s
local seconds = 3

local I_ball = mat3.diag(1, 1, 1) * (2 / 5 * mass * radius ^ 2)

-- Where the balls start: the first at L(sin θ₁, −cos θ₁) from the pivot, the second L further
-- along the second rod's direction.
local function start(t1, t2)
  local a1, a2 = math.rad(t1 or theta1), math.rad(t2 or theta2)
  local p1 = vec3(L * math.sin(a1), -L * math.cos(a1), 0)
  return p1, p1 + vec3(L * math.sin(a2), -L * math.cos(a2), 0)
end

-- The world: two balls, a hinge about z at the pivot (the origin) and one at the first ball.
local function hinged_world(integrator, t1, t2)
  local p1, p2 = start(t1, t2)
  local w = world{gravity = vec3(0, -g, 0), integrator = integrator}
  local b1 = w:add(body{mass = mass, inertia = I_ball, position = p1})
  local b2 = w:add(body{mass = mass, inertia = I_ball, position = p2})
  local j1 = w:add_joint{type = "hinge", a = b1, anchor = vec3(0, 0, 0), axis = vec3(0, 0, 1)}
  local j2 = w:add_joint{type = "hinge", a = b2, b = b1, anchor = p1, axis = vec3(0, 0, 1)}
  return w, b1, b2, j1, j2
end

-- The articulation: link 1 turns about z at the base, link 2 about z at the end of link 1;
-- each link's ball sits L down its link (q = 0 hangs straight down). q₂ is the second joint's
-- angle relative to link 1, so q = (θ₁, θ₂ − θ₁).
local function chain(perturbation, t1, t2)
  local art = articulation{gravity = vec3(0, -g, 0), integrator = "rk4"}
  local l1 = art:add_link{joint = "revolute", axis = vec3(0, 0, 1), origin = vec3(0, 0, 0),
                          mass = mass, com = vec3(0, -L, 0), inertia = I_ball}
  art:add_link{parent = l1, joint = "revolute", axis = vec3(0, 0, 1), origin = vec3(0, -L, 0),
               mass = mass, com = vec3(0, -L, 0), inertia = I_ball}
  t1, t2 = t1 or theta1, t2 or theta2
  art:set_state({math.rad(t1) + (perturbation or 0), math.rad(t2 - t1)}, {0, 0})
  return art
end

local function wrap(a) return math.atan(math.sin(a), math.cos(a)) end

local function world_angles(b1, b2)
  local d = b2.position - b1.position
  return math.atan(b1.position.x, -b1.position.y), math.atan(d.x, -d.y)
end

local function chain_angles(art)
  local q = art.q
  return q[1], q[1] + q[2]
end

-- E = m g y₁ + m g y₂ with the potential zero at the pivot (both at rest at the start).
local function closed_form_energy()
  local p1, p2 = start()
  return mass * g * (p1.y + p2.y)
end

local function on_the_second(time) return math.abs(time - math.floor(time + 0.5)) < dt / 2 end

return lesson{
  id = "double-pendulum",
  title = "A double pendulum, in full and in reduced coordinates",
  source = "000_3bd95e59483beea1.txt, \"Coordinate simulation\", \"Sequential impulses\"",
  steps = {
    {
      title = "Two ways to hold two rods together",
      text = [[
Two balls of 1 kg (radius 0.05 m, so nearly points) hang on rods of 1 m: the first from a
fixed pivot, the second from the first ball. Released from rest with the first rod at 120°
and the second at −30°, each measured from the downward vertical, under g = 9.80665 m/s².

000 "Coordinate simulation" describes two ways to simulate it. In full coordinates each
ball is a free body (6 numbers of position and 6 of velocity), and two hinge joints apply
impulses that cancel the relative motions the hinges forbid ("Sequential impulses"); nothing
but those impulses keeps the rods at their length, so a velocity-level solver lets them
drift and must pull them back. In reduced coordinates the state is only the two hinge
angles: the rods cannot stretch because there is nothing to stretch. The slides add that
reduced coordinates are "more vulnerable to numerical instability"; here both are stable,
and the instability we will meet is the pendulum's own.

The energy does not depend on the method. With the potential zero at the pivot, the balls
start at heights −cos 120° = 0.5 m and 0.5 − cos 30° = −0.366 m, so
E = g·(0.5 + 0.5 − cos 30°) = 1.31384 J, and without friction it must stay so.]],
      formula = "E = m·g·(y₁ + y₂) = g·(−cos θ₁ − cos θ₁ − cos θ₂)   (m = L = 1, at rest)",
      run = function(ctx)
        local p1, p2 = start()
        ctx:show("ball 1 at (m)", p1)
        ctx:show("ball 2 at (m)", p2)
        ctx:show("ball radius (m), inertia (2/5)mr² (kg·m²)", {radius, 2 / 5 * mass * radius ^ 2})
        local E = closed_form_energy()
        ctx:show("E = m g (y₁ + y₂) (J)", E)
        ctx:expect("E as the articulations issue gives it", E, 1.31384,
                   {abs = 5e-6, reason = "given to 5 decimals"})
        local w = hinged_world()
        local art = chain()
        ctx:show("world: w:energy() (J)", w:energy())
        ctx:show("articulation: art:energy() (J)", art:energy())
        ctx:expect("the world starts with E", w:energy(), E, 1e-12)
        ctx:expect("the articulation starts with E", art:energy(), E, 1e-12)
      end,
    },
    {
      title = "Energy and drift over 3 s",
      text = [[
Both run 3 s in steps of 1 ms: the world with its defaults (semi-implicit Euler, the
soft_step solver), the articulation with RK4 on its two angles (Featherstone's algorithm
gives their accelerations). The table samples every second: each one's energy, and the
largest position error either hinge of the world has had so far (j:error(): how far apart the two bodies' copies of the hinge
point are). The articulation has no such error: its second hinge is computed from the first
angle, so the rods keep their length to rounding.

Semi-implicit Euler does not keep the energy: it swings a few per cent about the right
value, most when the second ball whips round, without drifting away. RK4 holds it to 1e-7 in
the articulation (and, next step, to a fraction of a per cent in a world).]],
      run = function(ctx)
        local E = closed_form_energy()
        local semi, _, _, j1, j2 = hinged_world("semi_implicit")
        local art = chain()
        local rows, t, es, ea = {}, {}, {}, {}
        local worst = {semi = 0, art = 0}
        local drift, stretch = 0, 0
        for i = 1, math.floor(seconds / dt + 0.5) do
          semi:step(dt)
          art:step(dt)
          drift = math.max(drift, (j1:error()), (j2:error()))
          worst.semi = math.max(worst.semi, math.abs(semi:energy() - E))
          worst.art = math.max(worst.art, math.abs(art:energy() - E))
          local links = art.links
          local ball1 = links[1]:to_world(vec3(0, -L, 0))
          local ball2 = links[2]:to_world(vec3(0, -L, 0))
          stretch = math.max(stretch, math.abs(ball1:norm() - L), math.abs((ball2 - ball1):norm() - L))
          if i % 20 == 0 then
            t[#t + 1], es[#es + 1], ea[#ea + 1] = semi.time, semi:energy(), art:energy()
          end
          if on_the_second(semi.time) then
            rows[#rows + 1] = {semi.time, semi:energy(), art:energy(), drift}
          end
        end
        ctx:table({"t (s)", "E world (J)", "E articulation (J)", "hinge drift (m)"}, rows)
        ctx:plot{{x = t, y = es, label = "world, semi-implicit"}, {x = t, y = ea, label = "articulation, RK4"},
                 title = "Energy over time (J)", xlabel = "t (s)", ylabel = "E (J)", height = 10}
        ctx:show("largest |E − E₀|: world, articulation (J)", {worst.semi, worst.art})
        ctx:show("world: largest hinge position error (m)", drift)
        ctx:show("articulation: largest rod length error (m)", stretch)
        ctx:expect_range("articulation (RK4, 1 ms) keeps E to 1e-7", worst.art / E, nil, 1e-7)
        ctx:expect("articulation: rods keep their length", stretch, 0,
                   {abs = 1e-14, reason = "a length computed from angles, to rounding"})
        ctx:expect_range("world, semi-implicit: E within 5 %", worst.semi / E, nil, 0.05)
        ctx:expect_range("world: hinges drift less than 0.1 mm", drift, nil, 1e-4)
      end,
    },
    {
      title = "The two runs part",
      text = [[
The world (with RK4) and the articulation integrate the same equations, but not with the
same errors, and a double pendulum released high is chaotic: a small difference in the
angles grows roughly exponentially. From the release above it takes some 15 s to show; so
here both rods start at 150°, nearly upside down (E = 25.5 J).

First, over one second in steps of 1 ms, the two methods agree to better than 1e-4 rad (the
articulations issue's bound); with steps of 2 ms about four times worse, the world's error
being of second order in Δt. Then 6 s in steps of 2 ms: the chart shows, on a log scale,
the separation of the second rod's angle between world and articulation, and beside it the
separation between the articulation and a twin whose first angle starts 1e-9 rad away.
Both climb at about the same rate, so the parting is the pendulum's sensitivity, not a
fault of either method. The world's RK4 keeps the energy of this wilder motion to a fraction
of a per cent.]],
      run = function(ctx)
        local p1, p2 = start(high1, high2)
        ctx:show("ball 1 at (m)", p1)
        ctx:show("ball 2 at (m)", p2)
        local function second_angle_gap(b1, b2, art)
          local d = b2.position - b1.position
          local q = art.q
          return math.abs(wrap(math.atan(d.x, -d.y) - (q[1] + q[2])))
        end
        local first_second = {0, 0}
        local w1, c1, c2 = hinged_world("rk4", high1, high2)
        local art1 = chain(0, high1, high2)
        ctx:show("E (J)", art1:energy())
        for _ = 1, math.floor(1 / dt + 0.5) do
          w1:step(dt)
          art1:step(dt)
          first_second[1] = math.max(first_second[1], second_angle_gap(c1, c2, art1))
        end

        local step = 2 * dt
        local w, b1, b2 = hinged_world("rk4", high1, high2)
        local art, twin = chain(0, high1, high2), chain(1e-9, high1, high2)
        local t, world_vs_art, art_vs_art, rows = {}, {}, {}, {}
        local sep, twin_sep, E0, energy_gap = 0, 0, w:energy(), 0
        for i = 1, math.floor(6 / step + 0.5) do
          w:step(step)
          art:step(step)
          twin:step(step)
          local q, qt = art.q, twin.q
          sep = second_angle_gap(b1, b2, art)
          energy_gap = math.max(energy_gap, math.abs(w:energy() - E0))
          if w.time <= 1 + dt then first_second[2] = math.max(first_second[2], sep) end
          twin_sep = math.abs(wrap(qt[1] + qt[2] - q[1] - q[2]))
          if i % 10 == 0 then
            t[#t + 1] = w.time
            world_vs_art[#world_vs_art + 1] = math.log(math.max(sep, 1e-16), 10)
            art_vs_art[#art_vs_art + 1] = math.log(math.max(twin_sep, 1e-16), 10)
          end
          if i % 500 == 0 then rows[#rows + 1] = {w.time, sep, twin_sep} end
        end
        ctx:table({"t (s)", "|θ₂ world − θ₂ articulation|", "|θ₂ twin − θ₂|"}, rows)
        ctx:plot{{x = t, y = world_vs_art, label = "world vs articulation"},
                 {x = t, y = art_vs_art, label = "articulation vs twin (1e-9 rad)"},
                 title = "Separation of θ₂, log₁₀ rad", xlabel = "t (s)", ylabel = "log₁₀ rad",
                 height = 10}
        ctx:show("first second, 1 ms and 2 ms steps: largest gap (rad)", first_second)
        ctx:expect_range("1 ms: world and articulation agree over the first second", first_second[1],
                         nil, 1e-4)
        ctx:expect("2 ms: about four times further apart", first_second[2] / first_second[1], 4,
                   {rel = 0.1, reason = "second order in Δt, up to higher-order terms"})
        ctx:show("world (RK4, 2 ms): largest |E − E₀| over 6 s (J)", energy_gap)
        ctx:expect_range("world, RK4: E within 1 %", energy_gap / E0, nil, 0.01)
        ctx:expect_range("after 6 s the twin is 1e4 times further away", twin_sep / 1e-9, 1e4, nil)
        ctx:expect_range("after 6 s world and articulation have parted (rad)", sep, 0.1, nil)
      end,
    },
  },
}
