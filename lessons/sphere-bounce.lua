-- A ball dropped on a floor (001 "Collisions"): radius 0.35 m, restitution 0.75, friction
-- 0.6. Each rebound reaches e² = 0.5625 of the previous height; thrown sideways, friction
-- makes it spin until it rolls (v = ωR, at 5/7 of its sideways speed); without friction it
-- never spins.

local radius = 0.35          -- m, 001's SPHERE_RADIUS
local restitution = 0.75     -- 001's e (its code writes the factor 1 + e = 1.75)
local friction = 0.6         -- 001's friction
local mass = 1               -- kg (001 gives none; the outcome does not depend on it)
local drop_height = 2        -- m, from the floor to the bottom of the ball
local dt = 1 / 1200          -- s

-- Drops the ball on a floor y ≥ 0 and follows it for `duration` seconds. Returns the world,
-- the ball, the heights of the bottom of the ball at each apex after a bounce, the ball's
-- velocity and spin sampled just after the first bounce, the first contact seen, the number
-- of bounces and the time from which the ball stays on the floor. With `trace`, its t and y
-- lists get the height of the ball's bottom after every step.
local function drop(floor_friction, sideways_speed, duration, step, trace)
  step = step or dt
  local w = world{}
  w:add_plane{normal = vec3(0, 1, 0), offset = 0, restitution = restitution,
              friction = floor_friction}
  local ball = w:add(body.sphere{mass = mass, radius = radius, restitution = restitution,
                                 friction = floor_friction,
                                 position = vec3(0, radius + drop_height, 0),
                                 velocity = vec3(sideways_speed, 0, 0)})
  local apexes, after_first, rising, material = {}, nil, false, nil
  local bounces, resting_from, top = 0, 0, nil
  for i = 1, math.floor(duration / step + 0.5) do
    local vy_before = ball.velocity.y
    w:step(step)
    local vy = ball.velocity.y
    if vy_before <= 0 and vy > 0 then
      bounces = bounces + 1
      if not after_first then
        after_first = {velocity = ball.velocity, spin = ball.angular_velocity}
      end
    end
    local contact = w:contacts()[1]
    if contact and not material then material = contact end
    -- The apex: the highest position seen while the ball rises and turns.
    if vy > 0 then rising, top = true, math.max(top or 0, ball.position.y - radius) end
    if rising and vy <= 0 then
      apexes[#apexes + 1] = math.max(top, ball.position.y - radius)
      rising, top = false, nil
    end
    if ball.position.y - radius > 1e-6 then resting_from = i * step end
    if trace then  -- the height of the ball's bottom after each step, for a plot
      trace.t[#trace.t + 1], trace.y[#trace.y + 1] = w.time, ball.position.y - radius
    end
  end
  return w, ball, apexes, after_first, material, bounces, resting_from
end

return lesson{
  id = "sphere-bounce",
  title = "A ball on the floor: restitution, friction and rolling",
  source = "001_8a70f78e0cc79e25.txt, \"Collisions\"",
  steps = {
    {
      title = "Each bounce keeps e² of the height",
      text = [[
001 drops a ball of radius 0.35 m on a floor with restitution e = 0.75 (and gives no mass: the
bounces do not depend on it; ours is 1 kg). At each impact the
floor reverses the ball's vertical speed and scales it by e; since the height a ball rises
to grows with the square of its launch speed (h = v²/2g), each rebound reaches e² = 0.5625
of the previous one. From 2 m (the ball's centre starts at 2.35 m, its bottom 2 m above the
floor): 1.125 m, 0.633 m, 0.356 m, ... In rigidlab both the floor
(w:add_plane) and the ball carry a restitution and a friction; a contact uses the larger
restitution and the geometric mean of the frictions (Box2D's rule), so we give both 0.75
and 0.6. Like Box2D, the world also stops bouncing impacts slower than 1 m/s
(restitution_threshold), so after a few bounces the ball settles on the floor.

The world steps in time, 1/60 s here as in a game, so the ball rarely reaches the floor
exactly at the end of a step. Within a step every integrator moves the ball along a
parabola, so the world works out where in the step the ball meets the floor and with what
speed, lands it on the floor at the end of that step and sends it up in the next one with
e times the speed it met the floor with. The heights then keep e² at 60 Hz as at 1200 Hz;
what is left is that the apex is only seen at a step, at most g·Δt²/8 below the top of the
flight (0.34 mm at 60 Hz), which bounds the checks below. (Bouncing instead with the speed
the ball has after gravity was added for the whole step gains e·g·Δt per bounce: at 60 Hz
a ball with e = 0.9 would never settle.)

From 2 m the ball meets the floor at v₀ = √(2g·2) = 6.26 m/s, then at v₀eᵏ; the k-th impact
bounces while v₀eᵏ > 1 m/s, which holds for k = 0 … 6: 7 bounces. Each flight takes
2v₀eᵏ/g, so the ball is down for good after √(2h/g) + Σₖ₌₁⁷ 2v₀eᵏ/g = 3.96 s, give or take
a step per bounce (a ball that reaches the floor during a step bounces in the next).]],
      formula = "v' = e·v  ⇒  h' = v'²/(2g) = e²·h,   e² = 0.75² = 0.5625",
      run = function(ctx)
        local g, game_step = 9.81, 1 / 60
        local trace = {t = {0}, y = {drop_height}}
        local _, _, apexes, _, contact, bounces, resting_from = drop(friction, 0, 6, game_step, trace)
        ctx:plot{{x = trace.t, y = trace.y, label = "height of the ball's bottom"},
                 title = "Bounces at 60 Hz, each e² = 0.5625 as high", xlabel = "t (s)",
                 ylabel = "m", height = 10}
        ctx:show("the contact's restitution", contact.restitution)
        ctx:show("the contact's friction", contact.friction)
        ctx:show("the contact's normal", contact.normal)
        ctx:expect("e of the ball–floor pair = 0.75", contact.restitution, restitution)
        local rows, height = {}, drop_height
        -- Each apex is seen up to g Δt²/8 low; the drop height is exact.
        local seen = g * game_step ^ 2 / 8
        for n = 1, math.min(#apexes, 4) do
          height = height * restitution ^ 2
          local previous = n == 1 and drop_height or apexes[n - 1]
          rows[n] = {n, apexes[n], height, apexes[n] / previous}
          ctx:expect("bounce " .. n .. ": height ratio e² (60 Hz)", apexes[n] / previous,
                     restitution ^ 2, {abs = (n == 1 and 1 or 2) * seen / previous})
        end
        ctx:table({"bounce", "apex height (m)", "e²ⁿ·h₀ (m)", "ratio to previous"}, rows)
        local by_step = {}
        for i, step in ipairs({1 / 60, 1 / 300, 1 / 1200}) do
          local _, _, heights = drop(friction, 0, 3, step)
          local bound = g * step ^ 2 / 4 / heights[1]
          by_step[i] = {string.format("1/%d", math.floor(1 / step + 0.5)),
                        heights[2] / heights[1] - restitution ^ 2, bound}
          ctx:expect("Δt = " .. by_step[i][1] .. ": bounce 2 ratio within g Δt²/(4 h₁) of e²",
                     heights[2] / heights[1], restitution ^ 2, {abs = bound})
        end
        ctx:table({"Δt (s)", "bounce 2 ratio − e²", "bound g Δt²/(4 h₁)"}, by_step)
        local v0 = math.sqrt(2 * g * drop_height)
        local count, rest = 0, math.sqrt(2 * drop_height / g)
        while v0 * restitution ^ count > 1 do
          count = count + 1
          rest = rest + 2 * v0 * restitution ^ count / g
        end
        ctx:expect("bounces faster than 1 m/s: k = 0 … 6", bounces, count)
        ctx:show("at rest from (s)", resting_from)
        ctx:expect("at rest after √(2h/g) + Σ 2v₀eᵏ/g = 3.96 s (a step per bounce)",
                   resting_from, rest, {abs = (count + 1) * game_step})
      end,
    },
    {
      title = "Friction makes it spin, then roll",
      text = [[
Without friction the floor can only push straight up, through the centre of the ball, so
it cannot turn it. Friction acts at the contact point, sideways, 0.35 m below the centre,
and that lever arm makes a torque. Throw the ball sideways at 1 m/s: at the first impact
friction opposes the sliding of the contact point, slowing the centre and spinning the
ball up at the same time. For a solid ball (I = 2/5·mR²) the sliding stops when the centre
has kept 5/7 of its speed and the spin has reached ω = v/R: the ball rolls. Coulomb's law
allows up to μ times the normal impulse, far more than the 2/7·m·v needed here, so by the
end of the first impact the ball rolls (the world applies friction where the ball really
touches the floor, R below the centre, so this holds to rounding error), and it
goes on rolling at that speed: on a flat floor nothing slows a rolling ball.]],
      formula = "friction impulse j = (2/7)·m·v  ⇒  v' = (5/7)·v,   ω' = v'/R   (rolling)",
      run = function(ctx)
        local speed = 1
        local _, ball, _, first = drop(friction, speed, 6)
        ctx:show("after the first bounce: v (m/s)", first.velocity)
        ctx:show("after the first bounce: ω (rad/s)", first.spin)
        ctx:expect("v_x = 5/7 of 1 m/s", first.velocity.x, 5 / 7 * speed, {abs = 1e-12})
        ctx:expect("ω_z = −v_x/R (rolling toward +x)", first.spin.z, -first.velocity.x / radius,
                   {abs = 1e-12})
        ctx:show("after 6 s: v (m/s)", ball.velocity)
        ctx:show("after 6 s: ω (rad/s)", ball.angular_velocity)
        ctx:expect("still rolling after 6 s: ω_z·R = −v_x", ball.angular_velocity.z * radius,
                   -ball.velocity.x, {abs = 1e-12})
        ctx:expect("at 5/7 of 1 m/s", ball.velocity.x, 5 / 7 * speed, {abs = 1e-12})
      end,
    },
    {
      title = "No friction, no spin",
      text = [[
With friction 0 the same throw bounces exactly as before but never turns: every impulse
from the floor points straight up through the centre of mass, and a force through the
centre has no moment. The sideways speed is untouched too.

001's code for this contact has two slips worth knowing. It takes the ball's own contact
velocity as the relative velocity, then only applies impulses when that velocity points
away from the floor and pushes the ball down, two sign errors that cancel only if the
relative velocity is meant as floor minus ball. And its angular factor for friction is
(I⁻¹(R×t))·t, which for a ball is always zero; the right one is (R×t)·I⁻¹(R×t) = R²/I, so
its friction impulse is 3.5 times too large and, with 0.6, reverses the sliding instead of
stopping it: the contact would slide back at 1.1 times its old speed.]],
      formula = "μ = 0: every impulse ∥ n through the centre  ⇒  ω stays 0, v_x unchanged",
      run = function(ctx)
        local _, ball, apexes = drop(0, 1, 4)
        ctx:show("after 4 s: ω (rad/s)", ball.angular_velocity)
        ctx:show("after 4 s: v (m/s)", ball.velocity)
        ctx:expect("no spin", ball.angular_velocity, vec3(0, 0, 0), {abs = 1e-12})
        ctx:expect("sideways speed unchanged", ball.velocity.x, 1, 1e-12)
        ctx:expect("it did bounce", #apexes >= 3 and 1 or 0, 1)
        -- 001's friction step by hand, λ = −0.6·(v·t)/(1/m + angular factor), against the
        -- mass the contact point really has along t: t·M⁻¹t (002 "Inverse Mass Matrix").
        local R, t, slip = vec3(0, -radius, 0), vec3(1, 0, 0), 1
        local inverse_inertia = 1 / (0.4 * mass * radius ^ 2)
        local document_factor = (inverse_inertia * R:cross(t)):dot(t)
        local probe = body.sphere{mass = mass, radius = radius}
        local along_t = t:dot(collide.inverse_mass_matrix(probe, R, R) * t)
        ctx:show("001's angular factor (I⁻¹(R×t))·t (1/kg)", document_factor)
        ctx:show("t·M⁻¹t = 1/m + R²/I (1/kg)", along_t)
        ctx:expect("t·M⁻¹t = 1/m + 5/(2m) = 3.5/m", along_t, 3.5 / mass)
        local impulse = -friction * slip / (1 / mass + document_factor)
        local slip_after = slip + impulse * along_t
        ctx:show("contact slip after 001's friction impulse (m/s)", slip_after)
        ctx:expect("001's impulse reverses the slip: 1 − 0.6·3.5 = −1.1", slip_after, -1.1)
      end,
    },
    {
      title = "Watch it bounce",
      text = [[
The ball of step 1 (1 kg, radius 0.35 m, e = 0.75, μ = 0.6, its bottom 2 m above the floor,
its centre at x = -1.5 m)
thrown sideways at 1 m/s, in a world at 60 Hz, drawn every 0.8 s with the path of its
centre behind it. Each arc is lower than the one before, by e² = 0.5625 in height;
friction makes the ball spin at every touch (the great circles drawn on it turn). In a
terminal, v at the prompt shows it live: space pauses, ← steps back.]],
      formula = "apex after a bounce = e²·(height before);   E never rises",
      run = function(ctx)
        local w = world{}
        w:add_plane{normal = vec3(0, 1, 0), offset = 0, restitution = restitution,
                    friction = friction}
        local ball = w:add(body.sphere{mass = mass, radius = radius, restitution = restitution,
                                       friction = friction,
                                       position = vec3(-1.5, radius + drop_height, 0),
                                       velocity = vec3(1, 0, 0)})
        local E0 = w:energy()
        local rec = w:record{}
        ctx:motion(w, {seconds = 2.4, frames = 4, dt = 1 / 60, show = "trail",
                       camera = {eye = vec3(-0.3, 1.5, 4.5), target = vec3(-0.3, 1.1, 0)}})
        rec:stop()
        -- The first apex: the highest point after the ball first moved up.
        local heights, apex, rising = rec:series("position", ball), nil, false
        for k = 2, #heights do
          if heights[k].y > heights[k - 1].y then rising = true end
          if rising then apex = math.max(apex or 0, heights[k].y - radius) end
        end
        local seen = 9.81 * (1 / 60) ^ 2 / 8      -- an apex is seen up to g Δt²/8 low (step 1)
        ctx:show("first apex after the bounce (m)", apex)
        ctx:expect("apex = e²·2 m", apex, restitution ^ 2 * drop_height, {abs = 2 * seen})
        ctx:expect_range("energy after 2.4 s (J), never above E₀", w:energy(), nil, E0)
      end,
    },
  },
}
