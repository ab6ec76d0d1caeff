-- A box hung on a spring (001 "Springs"): Hooke's law F = k·x with 001's k = 15 N/m and a
-- damper of 1 N·s/m, from a point of the box to a fixed world target, under gravity. The box
-- bounces as a damped oscillator and settles mg/k below the target; attached off-centre, it
-- settles with its centre of mass straight below the attachment point.

local k, damping = 15, 1           -- N/m, N·s/m: 001's spring_stiffness and damping_magnitude
local mass = 1                     -- kg (001 gives no mass)
local g = 9.81                     -- m/s², rigidlab's default gravity (001's code uses 9.8)
local box_size = vec3(0.4, 0.4, 0.4)
local target = vec3(0, 2, 0)       -- m, the world point the spring pulls towards
local release = 0.1                -- m below the target, at rest

local deflection = mass * g / k    -- static deflection: k·d = m·g

-- The hanging box moves on the vertical line only: m·ÿ = −k(y − y₀) − c·ẏ − m·g, a damped
-- oscillator about y₀ − d with γ = c/(2m) and ω_d = √(k/m − γ²); released at rest at y₀ − s.
local function closed_form_height(t)
  local gamma = damping / (2 * mass)
  local omega_d = math.sqrt(k / mass - gamma ^ 2)
  local offset = deflection - release
  local swing = math.cos(omega_d * t) + gamma / omega_d * math.sin(omega_d * t)
  return target.y - deflection + offset * math.exp(-gamma * t) * swing
end

local function hanging_box(attachment)
  local w = world{integrator = "rk4"}
  local box = w:add(body.box{mass = mass, size = box_size,
                             position = target - vec3(0, release, 0) - attachment})
  w:add_spring{a = box, a_point = attachment, anchor = target, k = k, damping = damping}
  return w, box
end

return lesson{
  id = "spring",
  title = "A box on a spring: Hooke's law and the static deflection",
  source = "001_8a70f78e0cc79e25.txt, \"Springs\"",
  steps = {
    {
      title = "Hooke's law and where the box comes to rest",
      text = [[
A spring pulls in proportion to how far it is stretched: F = k·x, with x the vector from
the point on the body to the target, so the force always points back toward the target.
001's code uses a stiffness k = 15 N/m and adds a damper, a force proportional to how fast
x changes (1 N·s/m), which is what eventually stops the bouncing. Hang a 1 kg box (a cube of
0.4 m) from the target, 2 m up, by its centre and it comes to rest where the spring balances its weight: k·d = m·g,
so d = mg/k = 9.81/15 = 0.654 m below the target (0.6533 m with 001's g = 9.8).

Three details of 001's code are worth knowing when you copy it. It estimates the damper's
speed by a difference between frames, (x − x_previous)/Δt, and starts x_previous at zero,
so on the first frame a box starting 0.1 m from its target at 60 frames per second gets a
damper force of 1·0.1·60 = 6 N for nothing; it also declares that variable as
previous_length but uses previous_spring_len. rigidlab's spring uses the exact velocities of
the two ends instead, and applies the damper along the spring's line. And 001 applies
gravity as the impulse (0, −9.8, 0)·Δt through apply_linear_impulse, which multiplies by
the inverse mass: that gives the acceleration 9.8/m, right only for a 1 kg body, since the
impulse of gravity is m·g·Δt. (Our box has 1 kg, where the two agree.)]],
      formula = "F = k·x + c·dx/dt,   x = target − point;   at rest: k·d = m·g  ⇒  d = mg/k",
      run = function(ctx)
        ctx:show("k (N/m)", k)
        ctx:show("m·g (N)", mass * g)
        ctx:show("d = mg/k (m)", deflection)
        ctx:expect("d = 9.81/15", deflection, 0.654)
        ctx:show("with 001's g = 9.8: d (m)", mass * 9.8 / k)
      end,
    },
    {
      title = "Bouncing down to it",
      text = [[
Released at rest 0.1 m below the target, the box overshoots and bobs about the resting
height. Attached at the centre, it moves only up and down, and its motion is the damped
oscillator m·ÿ = −k·(stretch) − c·ẏ − m·g: it swings at ω_d = √(k/m − γ²) ≈ 3.84 rad/s
while the swings die away like e^{−γt}, γ = c/(2m) = 0.5 1/s. The world (RK4, Δt = 0.01 s)
follows that closed form to a few 1e-8 m (checked to 1e-7), and after 40 s, twenty decay
times, the box hangs mg/k below the target to better than 1e-8 m.]],
      formula = "y(t) = y₀ − d + (d − s)·e^{−γt}(cos ω_d t + (γ/ω_d) sin ω_d t),\n" ..
                "γ = c/(2m),  ω_d = √(k/m − γ²)",
      run = function(ctx)
        local w, box = hanging_box(vec3(0, 0, 0))
        ctx:show("box centre at release (m)", box.position)
        local rows, worst = {}, 0
        local trace = {t = {0}, world = {box.position.y}, closed = {closed_form_height(0)}}
        for i = 1, 800 do
          w:step(0.01, 5)
          local want = closed_form_height(w.time)
          worst = math.max(worst, math.abs(box.position.y - want))
          if i % 10 == 0 and w.time < 5.25 then rows[#rows + 1] = {w.time, box.position.y, want} end
          if w.time < 10 + 1e-9 then
            trace.t[i + 1], trace.world[i + 1], trace.closed[i + 1] = w.time, box.position.y, want
          end
        end
        ctx:table({"t (s)", "height, world (m)", "closed form (m)"}, rows)
        ctx:plot{{x = trace.t, y = trace.world, label = "the world (RK4)"},
                 {x = trace.t, y = trace.closed, label = "closed form"},
                 title = "Height of the box's centre, the first 10 s", xlabel = "t (s)",
                 ylabel = "m", height = 10}
        ctx:show("largest difference over 40 s (m)", worst)
        ctx:expect("the world follows the damped oscillator", worst, 0, {abs = 1e-7})
        ctx:show("box centre after 40 s (m)", box.position)
        ctx:expect("it rests mg/k below the target", box.position, target - vec3(0, deflection, 0),
                   {abs = 1e-8})
        ctx:expect("and no longer moves", box.velocity, vec3(0, 0, 0), {abs = 1e-8})
      end,
    },
    {
      title = "Hung by a corner",
      text = [[
001 attaches the spring to a point of the box that need not be its centre. Then gravity,
acting at the centre of mass, and the spring, acting at the attachment point, also exert a
torque on the box, and it turns until they are in line: at rest the centre of mass hangs
straight below the attachment point, at the distance between them, here the half-diagonal
of the cube, 0.346 m. The spring still carries the whole weight, so the attachment point
sits mg/k below the target, exactly as before.

The spring's damper only resists stretching, and a box swinging about its corner hardly
stretches it, so we add a little air drag (w:add_drag) to let it settle within a minute;
drag vanishes at rest, so it does not change where the box ends up.]],
      formula = "at rest: attachment = target − (mg/k)ŷ\n" ..
                "         centre = attachment − |r_attach|·ŷ",
      run = function(ctx)
        local corner = box_size / 2          -- body coordinates of the top corner
        local w, box = hanging_box(corner)
        ctx:show("box centre at release, the corner 0.1 m below the target (m)", box.position)
        w:add_drag{body = box, linear = 0.5, angular = 0.05}
        w:step(0.01, 8000)
        local attachment = box:to_world(corner)
        ctx:show("attachment point after 80 s (m)", attachment)
        ctx:show("centre of mass (m)", box.position)
        ctx:show("|r_attach| (m)", corner:norm())
        ctx:expect("attachment point mg/k below the target", attachment,
                   target - vec3(0, deflection, 0), {abs = 1e-8})
        ctx:expect("centre of mass straight below it", box.position,
                   attachment - vec3(0, corner:norm(), 0), {abs = 1e-8})
        ctx:expect("at rest", box.angular_velocity, vec3(0, 0, 0), {abs = 1e-8})
      end,
    },
  },
}
