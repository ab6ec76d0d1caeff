-- One frame of a particle system (000 "Particle system"): sum a constant force (gravity), a
-- position-dependent one (a force field) and a velocity-dependent one (drag), divide by the
-- mass, and integrate velocity and then position.

local mass = 2                       -- kg
local x0 = vec3(1, 2, 0)             -- m
local v0 = vec3(3, 0, 0)             -- m/s
local dt = 0.1                       -- s, one (slow) frame
local gravity = vec3(0, -9.81, 0)    -- m/s², rigidlab's default
local field_stiffness = 4            -- N/m: a field pulling toward the origin, F = −k·x
local drag_coefficient = 0.5         -- N·s/m: linear drag, F = −c·v

local function gravity_force() return gravity * mass end
-- (Subtracting from the zero vector, not scaling by a negative number, keeps zero components
-- +0 instead of printing as -0.)
local function field_force(x) return vec3() - x * field_stiffness end
local function drag_force(v) return vec3() - v * drag_coefficient end
local function net_force(x, v) return gravity_force() + field_force(x) + drag_force(v) end

-- The acceleration motion.simulate asks for: a = F/m.
local function acceleration(_, x, v) return net_force(x, v) / mass end

return lesson{
  id = "particle-system",
  title = "One frame of a particle system",
  source = "000_3bd95e59483beea1.txt, \"Particle system\"",
  steps = {
    {
      title = "Three kinds of force",
      text = [[
The simplest physics engine treats every object as a particle: a point with a mass, a
position and a velocity, and no orientation. What moves it is the sum of the forces on it,
and the slides sort those forces by what they depend on. Gravity is constant: m·g whatever
the particle does. A force field depends on where the particle is; ours pulls toward the
origin like a spring, −k·x. Drag depends on how fast it goes and always opposes the motion,
−c·v. (The slides also list collision forces, which appear only at events, and joint
constraints, which restrict the motion; the other lessons deal with those.)

Our particle: 2 kg at (1, 2, 0) m, moving at (3, 0, 0) m/s, with k = 4 N/m and
c = 0.5 N·s/m.]],
      formula = "F = m·g + (−k·x) + (−c·v)",
      run = function(ctx)
        ctx:show("gravity m·g (N)", gravity_force())
        ctx:show("field −k·x (N)", field_force(x0))
        ctx:show("drag −c·v (N)", drag_force(v0))
        local total = net_force(x0, v0)
        ctx:show("net force F (N)", total)
        -- (0, −19.62, 0) + (−4, −8, 0) + (−1.5, 0, 0)
        ctx:expect("F = (−5.5, −27.62, 0) N", total, vec3(-5.5, -27.62, 0), 1e-12)
      end,
    },
    {
      title = "From force to acceleration, then velocity, then position",
      text = [[
Newton's second law turns the net force into an acceleration, a = F/m. The frame then
integrates twice, in the order the slides give: first the velocity is advanced by a·Δt,
then the position by the new velocity times Δt. That order is semi-implicit Euler (see the
euler-car lesson for why the order matters). rigidlab's motion.simulate runs the frame;
we hand it a function that sums the forces and divides by the mass, exactly the first two
bullet points of the slide, and it does the integrating.

With Δt = 0.1 s: a = (−2.75, −13.81, 0) m/s², the velocity becomes (2.725, −1.381, 0) m/s
and the particle moves to (1.2725, 1.8619, 0) m.]],
      formula = "a = F/m,   v₁ = v₀ + a·Δt,   x₁ = x₀ + v₁·Δt",
      run = function(ctx)
        local calls = {}
        local function recording(t, x, v)
          calls[#calls + 1] = {t = t, x = x, v = v}
          return acceleration(t, x, v)
        end
        local frame = motion.simulate{method = "semi_implicit", accel = recording, x0 = x0,
                                      v0 = v0, dt = dt, steps = 1}
        local a = acceleration(0, x0, v0)
        ctx:show("a = F/m (m/s²)", a)
        ctx:show("forces evaluated", #calls)
        ctx:show("... at position (m)", calls[1].x)
        ctx:show("... with velocity (m/s)", calls[1].v)
        ctx:show("v₁ (m/s)", frame.v[2])
        ctx:show("x₁ (m)", frame.x[2])
        ctx:expect("a = F/m = (−2.75, −13.81, 0)", a, vec3(-2.75, -13.81, 0), 1e-12)
        ctx:expect("the forces are summed once, at the frame's start", #calls, 1)
        ctx:expect("v₁ = v₀ + a·Δt = (2.725, −1.381, 0)", frame.v[2],
                   vec3(2.725, -1.381, 0), 1e-12)
        ctx:expect("x₁ = x₀ + v₁·Δt = (1.2725, 1.8619, 0)", frame.x[2],
                   vec3(1.2725, 1.8619, 0), 1e-12)
      end,
    },
    {
      title = "The loop, frame after frame",
      text = [[
A game repeats this recipe every frame: sum the forces at the current state, divide by the
mass, update velocity, update position. Because the field and the drag depend on the state,
the net force is different every frame, so it must be recomputed each time; only gravity
stays put. Here are five frames computed two ways: by motion.simulate, and by the recipe
written out in four lines of Lua right in this lesson. They agree to rounding.]],
      formula = "each frame: F = ΣFᵢ(x, v),  a = F/m,  v += a·Δt,  x += v·Δt",
      run = function(ctx)
        local frames = 5
        local engine = motion.simulate{method = "semi_implicit", accel = acceleration, x0 = x0,
                                       v0 = v0, dt = dt, steps = frames}
        local x, v = x0, v0
        local rows, worst = {}, 0
        for i = 1, frames + 1 do
          if i > 1 then
            local a = net_force(x, v) / mass
            v = v + a * dt
            x = x + v * dt
          end
          worst = math.max(worst, (engine.x[i] - x):norm(), (engine.v[i] - v):norm())
          local force = net_force(engine.x[i], engine.v[i])
          local function g6(value) return string.format("%.6g", value) end   -- fits 80 columns
          rows[i] = {engine.t[i], g6(engine.x[i].x), g6(engine.x[i].y), g6(engine.v[i].x),
                     g6(engine.v[i].y), g6(force.x), g6(force.y)}
        end
        ctx:table({"t (s)", "x (m)", "y (m)", "vx (m/s)", "vy (m/s)", "Fx (N)", "Fy (N)"}, rows)
        ctx:expect("motion.simulate = the recipe by hand, largest difference", worst, 0,
                   {abs = 1e-12})
      end,
    },
    {
      title = "The same frame in a rigidlab world",
      text = [[
A rigidlab world runs exactly this loop for all its bodies. Gravity is built in (the
default g = (0, −9.81, 0) m/s²), and any other force is added by a function the world
calls at the start of each step, here the field and the drag evaluated at the body's
current position and velocity. One step of 0.1 s with the default semi-implicit
integrator must land the 2 kg ball where our hand calculation did.]],
      formula = "w:add_force(fn): fn applies −k·x − c·v;  w:step(Δt)",
      run = function(ctx)
        local w = world{}
        local ball = w:add(body.sphere{mass = mass, radius = 0.1, position = x0, velocity = v0})
        w:add_force(function()
          ball:apply_force(field_force(ball.position) + drag_force(ball.velocity))
        end)
        w:step(dt)
        ctx:show("world gravity (m/s²)", w.gravity)
        ctx:show("v after one step (m/s)", ball.velocity)
        ctx:show("x after one step (m)", ball.position)
        ctx:expect("v₁ = (2.725, −1.381, 0)", ball.velocity, vec3(2.725, -1.381, 0), 1e-12)
        ctx:expect("x₁ = (1.2725, 1.8619, 0)", ball.position, vec3(1.2725, 1.8619, 0), 1e-12)
      end,
    },
  },
}
