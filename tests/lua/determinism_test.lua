-- Determinism: the same script gives bit-identical results, run after run. A scene of 100
-- spheres and boxes dropped in a heap onto a floor (hundreds of contacts every step, warm
-- starting, friction, restitution) is stepped 1,000 times at 60 Hz; the full state of every
-- body (position, orientation, velocity, angular velocity, bit for bit) and the world's time
-- are hashed (FNV-1a, 64 bits) and compared with the hash stored below, which was recorded when
-- the test was written. The same scene is also built twice in one process and the two worlds
-- must agree bit for bit, so a change of hash means the physics changed (update the stored
-- value in the same commit, saying why), not that rigidlab became nondeterministic.
local T = dofile("testing.lua")

local STORED_HASH = "9e9f2bf80fbf4aee"

-- A tiny linear congruential generator, so the scene does not depend on math.random.
local function generator(seed)
  local state = seed
  return function()
    state = (state * 6364136223846793005 + 1442695040888963407) & 0x7fffffffffffffff
    return (state >> 11) / (1 << 52)  -- in [0, 1)
  end
end

local function build_scene()
  local w = world{gravity = vec3(0, -9.81, 0)}
  w:add_plane{normal = vec3(0, 1, 0), offset = 0, friction = 0.5, restitution = 0.2}
  local random = generator(2026)
  for i = 0, 99 do
    -- a 5 x 5 footprint, four layers: neighbours overlap in x and z, so they hit each other
    local x, z, layer = i % 5, (i // 5) % 5, i // 25
    local position = vec3(x * 0.9 + 0.2 * random(), 0.6 + layer * 1.1 + 0.3 * random(),
                          z * 0.9 + 0.2 * random())
    local spin = vec3(random() - 0.5, random() - 0.5, random() - 0.5) * 4
    local b
    if i % 2 == 0 then
      b = body.sphere{mass = 0.5 + random(), radius = 0.3 + 0.15 * random(), position = position,
                      angular_velocity = spin, restitution = 0.3, friction = 0.6}
    else
      b = body.box{mass = 0.5 + random(), size = vec3(0.5 + 0.3 * random(), 0.4 + 0.3 * random(),
                   0.5 + 0.3 * random()), position = position,
                   orientation = quat.axis_angle(vec3(random(), 1, random()), 3 * random()),
                   angular_velocity = spin, friction = 0.7}
    end
    w:add(b)
  end
  return w
end

-- FNV-1a over the IEEE-754 bytes of every number (string.pack "<d": little-endian doubles).
local function state_hash(w)
  local hash = 0xcbf29ce484222325
  local function feed(...)
    local bytes = string.pack("<" .. string.rep("d", select("#", ...)), ...)
    for k = 1, #bytes do hash = (hash ~ bytes:byte(k)) * 0x100000001b3 end
  end
  feed(w.time)
  for _, b in ipairs(w:bodies()) do
    feed(b.position.x, b.position.y, b.position.z)
    feed(b.orientation.w, b.orientation.x, b.orientation.y, b.orientation.z)
    feed(b.velocity.x, b.velocity.y, b.velocity.z)
    feed(b.angular_velocity.x, b.angular_velocity.y, b.angular_velocity.z)
  end
  return string.format("%016x", hash)
end

local first, second = build_scene(), build_scene()
local contacts_seen = 0
for _ = 1, 1000 do
  first:step(1 / 60)
  contacts_seen = math.max(contacts_seen, #first:contacts())
end
second:step(1 / 60, 1000)

T.case("the scene has contacts to resolve", function()
  assert(contacts_seen >= 100, "only " .. contacts_seen .. " contacts at most in a step")
end)

T.case("the heap has collapsed onto the floor and nothing flew off", function()
  -- (spheres keep rolling: there is no rolling resistance; boxes come to rest)
  for i, b in ipairs(first:bodies()) do
    assert(b.position.y > 0 and b.position.y < 2, "body " .. i .. " at " .. tostring(b.position))
    assert(b.velocity:norm() < 5, "body " .. i .. " moves at " .. tostring(b.velocity))
    if b.shape == "box" then
      assert(b.velocity:norm() < 0.05, "box " .. i .. " still moves at " .. tostring(b.velocity))
    end
  end
end)

T.case("two runs in one process agree bit for bit", function()
  T.equal(state_hash(first), state_hash(second), "hash of the second world")
end)

T.case("the state after 1,000 steps has the stored hash", function()
  T.equal(state_hash(first), STORED_HASH, "hash of the state")
end)

T.finish()
