-- Newton's cradle (001 "Collisions"; 003 "Collision Response"): five equal balls on strings,
-- elastic. One in, one out; two in, two out; momentum and energy kept. The conservation laws
-- alone allow other answers: for one ball hitting two, impulses one contact at a time give
-- (0, 0, 3) and both contacts at once give (−1, 2, 2), and both keep momentum and energy.

local mass = 0.2          -- kg, each ball
local radius = 0.05       -- m
local length = 1          -- m, each string, from its hook to the ball's centre
local gap = 0.005         -- m, between neighbouring balls at rest
local speed = 3           -- m/s, the incoming ball(s)
local g = 9.81
local frame = 1 / 60
local substeps = 8

-- 003 "Collision Response" for a pair along n (from 1 to 2), no friction, no rotation: the
-- impulse p̂ = (1 + e)(v2 − v1)·n/(1/m1 + 1/m2) on body 1 and −p̂ on body 2. (003 writes the
-- restitution relation without its minus sign; the impulse formula is right.)
local function pair(v1, v2, m1, m2, e)
  local p = (1 + e) * (v2 - v1) / (1 / m1 + 1 / m2)
  return v1 + p / m1, v2 - p / m2, p
end

-- Sequential impulses, one contact at a time, until no neighbours close in on each other.
local function sequential(v)
  v = {table.unpack(v)}
  local log = {}
  repeat
    local changed = false
    for i = 1, #v - 1 do
      if v[i] > v[i + 1] + 1e-15 then
        local p
        v[i], v[i + 1], p = pair(v[i], v[i + 1], mass, mass, 1)
        log[#log + 1] = {i, i + 1, -p}
        changed = true
      end
    end
  until not changed
  return v, log
end

local function momentum(v) local s = 0 for _, x in ipairs(v) do s = s + mass * x end return s end
local function energy(v) local s = 0 for _, x in ipairs(v) do s = s + 0.5 * mass * x * x end return s end

-- Three balls, both contacts at once: each closing speed reversed (e = 1) and momentum kept.
-- v2' − v1' = v1 − v2, v3' − v2' = v2 − v3, Σv' = Σv: three linear equations, solved here.
local function simultaneous3(v)
  local d12, d23, p = v[1] - v[2], v[2] - v[3], v[1] + v[2] + v[3]
  local v1 = (p - 2 * d12 - d23) / 3
  return {v1, v1 + d12, v1 + d12 + d23}
end

-- The cradle: ball i hangs from a hook at (x_i, length, 0) on a string (a distance joint) and
-- rests at (x_i, 0, 0); the balls `moving` start with `speed` along +x.
local function cradle(moving, spacing)
  local w = world{substeps = substeps}
  local balls = {}
  for i = 1, 5 do
    local x = (i - 1) * (2 * radius + spacing)
    balls[i] = w:add(body.sphere{mass = mass, radius = radius, position = vec3(x, 0, 0),
                                 velocity = vec3(i <= moving and speed or 0, 0, 0),
                                 restitution = 1, friction = 0})
    w:add_joint{type = "distance", a = balls[i], a_point = vec3(0, 0, 0),
                b_point = vec3(x, length, 0)}
  end
  return w, balls
end

-- Runs `seconds`; returns the highest each ball rose and the traces of their x displacements.
local function swing(moving, spacing, seconds)
  local w, balls = cradle(moving, spacing)
  local E0 = w:energy()
  local highest, t, xs = {0, 0, 0, 0, 0}, {0}, {{}, {}, {}, {}, {}}
  local rest = {}
  for i, b in ipairs(balls) do rest[i] = b.position.x; xs[i][1] = 0 end
  for k = 1, math.floor(seconds / frame + 0.5) do
    w:step(frame)
    t[k + 1] = w.time
    for i, b in ipairs(balls) do
      highest[i] = math.max(highest[i], b.position.y)
      xs[i][k + 1] = b.position.x - rest[i]
    end
  end
  return highest, t, xs, E0, w:energy()
end

return lesson{
  id = "newtons-cradle",
  title = "Newton's cradle: one in, one out",
  source = "001_8a70f78e0cc79e25.txt, \"Collisions\"; 003_636de12a6b81385f.txt, \"Collision Response\"",
  steps = {
    {
      title = "One contact at a time",
      text = [[
Five steel balls of 0.2 kg hang in a row on strings; the first comes in at 3 m/s. Each
contact is a collision of 003 "Collision Response" without friction or rotation, elastic
(e = 1): the impulse p̂ = (1 + e)(v₂ − v₁)·n/(1/m₁ + 1/m₂). For equal masses it swaps the two
velocities. Applied one contact at a time, as 000's sequential impulses or 001 "Collisions"
handle contacts, the swaps pass the 3 m/s along the row: ball 1 gives it to 2, 2 to 3, and
so on, until ball 5 leaves alone. Two balls in: the same swaps, twice, and two leave.

(003 states the restitution law as (v₂' − v₁') = ε(v₂ − v₁), without the minus sign: after
the collision the bodies separate, so the relative velocity along n changes sign,
(v₂' − v₁')·n = −ε(v₂ − v₁)·n. Its impulse formula is the right one.)]],
      formula = "p̂ = (1 + e)·(v₂ − v₁)·n / (1/m₁ + 1/m₂)\ne = 1, m₁ = m₂:  v₁' = v₂,  v₂' = v₁",
      run = function(ctx)
        for _, moving in ipairs{1, 2} do
          local before = {}
          for i = 1, 5 do before[i] = i <= moving and speed or 0 end
          local after, log = sequential(before)
          local want = {}
          for i = 1, 5 do want[i] = i > 5 - moving and speed or 0 end
          ctx:show(string.format("%d in: before (m/s)", moving), before)
          ctx:show(string.format("%d in: impulses, by contact", moving), #log)
          ctx:show(string.format("%d in: after (m/s)", moving), after)
          ctx:expect(string.format("%d in, %d out", moving, moving), after, want)
          ctx:expect("momentum kept", momentum(after), momentum(before))
          ctx:expect("energy kept", energy(after), energy(before))
        end
      end,
    },
    {
      title = "Conservation alone does not decide",
      text = [[
Why not two balls out at 1.5 m/s each? That keeps the momentum (0.2·3 = 0.6 N·s) but has half
the energy: with n balls leaving at 3/n m/s the energy is 0.9/n J, right only for n = 1. So
momentum and energy together forbid it. But they do not pin the answer down: take one
ball hitting two at rest. One contact at a time gives (0, 0, 3). Both contacts at once
(the same impulse problem solved as one system, each closing speed reversed) gives
(−1, 2, 2): the first ball bounces back and the other two leave together. Both keep momentum
(0.6 N·s) and energy (0.9 J). Which one a simulation shows depends on how its solver orders
the contacts; a real cradle behaves like the first, because its hard balls pass the blow
through one contact before the next one feels it.]],
      formula = "Σ m v' = Σ m v,   Σ ½ m v'² = Σ ½ m v²\n(two equations for three unknowns)",
      run = function(ctx)
        local rows = {}
        for n = 1, 4 do rows[n] = {n, 3 / n, momentum({3 / n}) * n, n * 0.5 * mass * (3 / n) ^ 2} end
        ctx:table({"balls out", "each at (m/s)", "momentum (N·s)", "energy (J)"}, rows)
        local seq = sequential({speed, 0, 0})
        local sim = simultaneous3({speed, 0, 0})
        ctx:show("one contact at a time (m/s)", seq)
        ctx:show("both at once (m/s)", sim)
        ctx:expect("sequential: (0, 0, 3)", seq, {0, 0, 3})
        ctx:expect("simultaneous: (−1, 2, 2)", sim, {-1, 2, 2})
        ctx:expect("both keep momentum", momentum(sim), momentum(seq))
        ctx:expect("both keep energy", energy(sim), energy(seq))
      end,
    },
    {
      title = "The cradle in a world",
      text = [[
Now a world: five balls of radius 0.05 m, 5 mm apart, each on a string of 1 m (a distance
joint from a hook straight above it), restitution 1, no friction, 60 Hz with 8 substeps.
Ball 1 starts at the bottom at 3 m/s. With the small gaps the contacts are met one after
the other, so the solver meets them one at a time. Ball 5 then leaves with all the energy
and rises until it has none left: h = v²/(2g) = 0.459 m. The others stay nearly at the
bottom: nearly, because ball 1 meets ball 2 after swinging 5 mm on its string, its path
tilted by gap/L = 0.005 rad, so about 3·0.005 = 0.015 m/s of its velocity is not along the
row; that is a rise of some (0.015)²/(2g) ≈ 1e-5 m, and we allow 1e-4 m. Then ball 5 swings
back, and ball 1 goes out: the chart follows each ball's sideways displacement for 3 s, and
the film strip shows the first 0.6 s (rigidlab view, or w:view{} in the REPL, shows it live).]],
      formula = "h = v² / (2g)",
      run = function(ctx)
        local h = speed ^ 2 / (2 * g)
        local x = {}
        for i = 1, 5 do x[i] = (i - 1) * (2 * radius + gap) end
        ctx:show("balls at x (m), y = 0", x)
        ctx:show("h = v²/(2g) (m)", h)
        local highest, _, _, E0, E1 = swing(1, gap, 0.6)
        local _, t, xs, _, E3 = swing(1, gap, 3)
        ctx:show("highest each ball rose in the first 0.6 s (m)", highest)
        ctx:show("energy at the start, after 0.6 s, after 3 s (J)", {E0, E1, E3})
        ctx:plot{{x = t, y = xs[1], label = "ball 1"}, {x = t, y = xs[3], label = "ball 3"},
                 {x = t, y = xs[5], label = "ball 5"}, title = "One in, one out",
                 xlabel = "t (s)", ylabel = "sideways (m)", height = 10}
        ctx:expect("ball 5 rises to v²/(2g)", highest[5], h,
                   {rel = 2e-3, reason = "the world keeps the energy to 0.1 % (above)"})
        ctx:expect_range("the world keeps the energy to 0.1 % (J)", math.abs(E1 - E0), nil, 0.9e-3)
        ctx:expect_range("and to 1 % over 3 s, three collisions (J)", math.abs(E3 - E0), nil, 0.9e-2)
        for i = 2, 4 do
          ctx:expect_range(string.format("ball %d stays down (m)", i), highest[i], nil, 1e-4)
        end
        local film, film_balls = cradle(1, gap)
        ctx:motion(film, {seconds = 0.6, frames = 4})
        local b5 = film_balls[5]
        local swing_energy = mass * g * b5.position.y + 0.5 * mass * b5.velocity:dot(b5.velocity)
        ctx:show("after 0.6 s, ball 5's energy m·g·y + ½mv² (J)", swing_energy)
        ctx:expect("ball 5 carries all the energy", swing_energy, 0.5 * mass * speed ^ 2,
                   {rel = 2e-3, reason = "the world keeps the energy to 0.1 % (above)"})
      end,
    },
    {
      title = "Two in, two out",
      text = [[
Balls 1 and 2 start at 3 m/s together. One contact at a time, balls 4 and 5 leave and each
rises to 0.459 m; the three others stay at the bottom, up to the same small tilt.]],
      run = function(ctx)
        local h = speed ^ 2 / (2 * g)
        local highest, _, _, E0, E1 = swing(2, gap, 0.6)
        ctx:show("highest each ball rose in 0.6 s (m)", highest)
        ctx:show("energy at the start, after 0.6 s (J)", {E0, E1})
        ctx:expect("ball 4 rises to v²/(2g)", highest[4], h,
                   {rel = 2e-3, reason = "the world keeps the energy to 0.2 %"})
        ctx:expect("ball 5 rises to v²/(2g)", highest[5], h,
                   {rel = 2e-3, reason = "the world keeps the energy to 0.2 %"})
        for i = 1, 3 do
          ctx:expect_range(string.format("ball %d stays down (m)", i), highest[i], nil, 1e-4)
        end
      end,
    },
    {
      title = "Touching balls: all contacts at once",
      text = [[
Hang the five balls touching (no gap) and send ball 1 in at 3 m/s: now all four contacts
are in the world's solver in the same step, and it solves them together, as one system:
each contact's closing speed before the step (3 m/s for the first, 0 for the others) is
reversed, and momentum is kept. That is the simultaneous answer of step 2, for five balls:
v₂' − v₁' = 3 and v₅' = v₄' = v₃' = v₂', so 5v₁' + 12 = 3: ball 1 bounces back at −1.8 m/s
and the four others leave together at 1.2 m/s, which keeps momentum and energy too (as it
does for any number of balls). A real cradle does not do that; this is why the world above
hangs its balls 5 mm apart. We look one frame after the start: within it the balls have
begun to swing on their strings, so gravity has changed them by up to g·(x/L)·Δt ≈ 2e-3 m/s.]],
      formula = "v₂' − v₁' = v,  v₃' = v₄' = v₅' = v₂',  Σv' = v\n⇒   v₁' = −0.6v,  v₂' = … = v₅' = 0.4v",
      run = function(ctx)
        local n = 5
        local v1 = speed * (2 - n) / n
        local want = {v1, v1 + speed, v1 + speed, v1 + speed, v1 + speed}
        ctx:show("simultaneous, closed form (m/s)", want)
        ctx:expect("it keeps momentum", momentum(want), mass * speed)
        ctx:expect("it keeps energy", energy(want), 0.5 * mass * speed ^ 2)
        local w, balls = cradle(1, 0)
        ctx:show("balls at x (m), touching", {0, 0.1, 0.2, 0.3, 0.4})
        w:step(frame)
        local got = {}
        for i, b in ipairs(balls) do got[i] = b.velocity.x end
        ctx:show("the world after one frame (m/s)", got)
        ctx:expect("touching balls: the simultaneous answer", got, want,
                   {abs = 5e-3, reason = "a frame of swinging on the strings, about 2e-3 m/s"})
      end,
    },
  },
}
