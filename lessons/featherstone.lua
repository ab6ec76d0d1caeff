-- Featherstone's articulated-body algorithm on a 3-link pendulum, one loop at a time: every
-- quantity of the document's three loops printed and checked against its closed form, and the
-- resulting accelerations against M⁻¹(τ − C q̇ − g) from the mass matrix.

local L, m = 1.0, 1.0                          -- each link: a uniform rod of 1 m and 1 kg
local rod = mat3.diag(m * L * L / 12, 0, m * L * L / 12)  -- about its COM, rod along y
local g = 9.81

-- A planar chain hanging along −y from revolute joints about z, one rod per link.
local function chain()
  local art = articulation{gravity = vec3(0, -g, 0)}
  local parent
  for k = 1, 3 do
    parent = art:add_link{parent = parent, origin = k == 1 and vec3() or vec3(0, -L, 0),
                          mass = m, com = vec3(0, -L / 2, 0), inertia = rod}
  end
  return art
end

local q0 = {0.3, -0.2, 0.4}    -- rad, each joint relative to the link before
local qd0 = {0.5, -0.3, 0.8}   -- rad/s

-- Absolute angles φₖ = q₁ + … + qₖ and rates φ̇ₖ.
local function absolute(list)
  local out, sum = {}, 0
  for k, x in ipairs(list) do sum = sum + x; out[k] = sum end
  return out
end

-- x solving A x = b (rows of A), by Gaussian elimination with partial pivoting.
local function solve(A, b)
  local n, M = #b, {}
  for i = 1, n do M[i] = {table.unpack(A[i])}; M[i][n + 1] = b[i] end
  for c = 1, n do
    local p = c
    for r = c + 1, n do if math.abs(M[r][c]) > math.abs(M[p][c]) then p = r end end
    M[c], M[p] = M[p], M[c]
    for r = c + 1, n do
      local f = M[r][c] / M[c][c]
      for k = c, n + 1 do M[r][k] = M[r][k] - f * M[c][k] end
    end
  end
  local x = {}
  for i = n, 1, -1 do
    local s = M[i][n + 1]
    for k = i + 1, n do s = s - M[i][k] * x[k] end
    x[i] = s / M[i][i]
  end
  return x
end

-- The six numbers of a spatial vector as (angular; linear) vec3 pairs.
local function angular(s) return vec3(s[1], s[2], s[3]) end
local function linear(s) return vec3(s[4], s[5], s[6]) end

-- Rotates a world vector into the frame of a link turned by φ about z: R_z(φ)ᵀ w.
local function into_link(w, phi)
  local c, s = math.cos(phi), math.sin(phi)
  return vec3(c * w.x + s * w.y, -s * w.x + c * w.y, w.z)
end

return lesson{
  id = "featherstone",
  title = "Featherstone's algorithm: three loops over the links",
  source = "000_3bd95e59483beea1.txt, \"Coordinate simulation\", \"Featherstone's Algorithm\"",
  steps = {
    {
      title = "Reduced coordinates",
      text = [[
A chain of three rods hinged end to end could be simulated as three free bodies (18
coordinates) held together by hinge constraints that remove 5 freedoms each, with impulses
correcting the drift: 000 "Coordinate simulation" calls that full-coordinate simulation.
Reduced coordinates keep only what can move: one angle per hinge, q = (q₁, q₂, q₃), each
measured from the link before. The joints cannot come apart because nothing else is
stored. Every link's pose follows from q: with absolute angles φₖ = q₁ + … + qₖ, hinge k + 1
sits at hinge k plus L(sin φₖ, −cos φₖ).

First the simplest case, a published reference: one link of mass 1 with its COM 1 m out
along x, I_c = E, at rest under g = 9.81 (RBDL's test suite, DynamicsTests). Its angular
acceleration is the gravity torque over the inertia about the hinge, −m g L / (I_zz + m L²).]],
      formula = "q̈ = −m g L / (I_zz + m L²) = −9.81 / 2 = −4.905 rad/s²",
      run = function(ctx)
        local one = articulation{gravity = vec3(0, -g, 0)}
        one:add_link{mass = 1, com = vec3(1, 0, 0), inertia = mat3.diag(1, 1, 1)}
        ctx:expect("one link at rest: q̈", one:forward_dynamics()[1], -4.905, 1e-12)

        local art = chain()
        art:set_state(q0, qd0)
        ctx:show("q (rad)", art.q)
        ctx:expect("coordinates stored", #art.q, 3)
        local phi, hinge = absolute(q0), vec3()
        for k = 1, 3 do
          ctx:expect("hinge " .. k .. " position", art.links[k]:position(), hinge, 1e-14)
          hinge = hinge + vec3(L * math.sin(phi[k]), -L * math.cos(phi[k]), 0)
        end
      end,
    },
    {
      title = "Loop 1: velocities, velocity terms and bias forces",
      text = [[
The first loop goes from the base out (000 "Featherstone's Algorithm"): each link's velocity
is its parent's, carried into the link's frame, plus what its own joint adds,
vᵢ = R vⱼ + sᵢ q̇ᵢ. These are spatial velocities: six numbers, the angular velocity ω and
the velocity of the link point at the frame origin, both in link coordinates. For a hinge
about z, s = (0, 0, 1, 0, 0, 0). In the plane ω = (0, 0, φ̇ₖ), and the hinge of link k moves
with Σⱼ<ₖ L φ̇ⱼ (cos φⱼ, sin φⱼ) in the world, turned by −φₖ into the link's frame.

The loop also prepares cᵢ = vᵢ × sᵢ q̇ᵢ, the acceleration that appears just because the
joint moves while its axis is carried along (here (0, 0, 0, q̇ v_y, −q̇ v_x, 0)), and the
bias force pᵢ = vᵢ × Iᵢvᵢ − F_ext: the force the link alone needs to keep moving as it
does, minus the external forces (its weight). Its linear part is ω × (m v_com) − m g.

The slide writes "j ← i − 1, the parent of link i": true for a chain; in a tree j is the
parent whatever its number.]],
      formula = "vᵢ = R vⱼ + sᵢ q̇ᵢ     cᵢ = vᵢ × sᵢ q̇ᵢ     pᵢ = vᵢ × Iᵢ vᵢ − F_ext,ᵢ",
      run = function(ctx)
        local art = chain()
        art:set_state(q0, qd0)
        local trace = art:aba_trace({0, 0, 0})
        local phi, rate = absolute(q0), absolute(qd0)
        local hinge_velocity = vec3()
        for k = 1, 3 do
          local loops = trace.links[k]
          ctx:show("v" .. k .. " (rad/s; m/s)", loops.v)
          ctx:expect("ω" .. k .. " = (0, 0, φ̇" .. k .. ")", angular(loops.v), vec3(0, 0, rate[k]),
                     1e-14)
          local v_link = into_link(hinge_velocity, phi[k])
          ctx:expect("hinge " .. k .. " velocity in link " .. k, linear(loops.v), v_link, 1e-14)
          ctx:show("c" .. k, loops.c)
          ctx:expect("c" .. k .. " = (0, 0, 0, q̇ v_y, −q̇ v_x, 0)", loops.c,
                     {0, 0, 0, qd0[k] * v_link.y, -qd0[k] * v_link.x, 0}, 1e-14)
          local w = vec3(0, 0, rate[k])
          local v_com = v_link + w:cross(vec3(0, -L / 2, 0))
          local weight = into_link(vec3(0, -m * g, 0), phi[k])
          ctx:show("p" .. k, loops.p)
          ctx:expect("linear part of p" .. k .. " = ω × m v_com − m g", linear(loops.p),
                     w:cross(v_com * m) - weight, 1e-13)
          hinge_velocity = hinge_velocity + vec3(math.cos(phi[k]), math.sin(phi[k]), 0) *
                                            (L * rate[k])
        end
      end,
    },
    {
      title = "Loop 2: articulated inertias and bias forces",
      text = [[
The second loop goes from the tips back to the base. It starts each link's articulated
inertia and bias force from its own, I^accu = Iᵢ and p^accu = pᵢ, and adds what every child
hands over through its joint. A child does not weigh on its parent with its full inertia:
its joint lets it swing, so along s its inertia does not resist. What the parent feels is
I^accu − h hᵀ/d, with h = I^accu s and d = sᵀ h, the child's inertia about its own axis.
The bias force handed over is p^accu + I^accu c + (u/d) h, where u = τ − hᵀc − sᵀp^accu is
the part of the joint torque not already spent.

Two remarks on our copy of the slide: the update of the bias force reads "p^accu ← I^accu +
R(...)" where p^accu + R(...) is meant, and the line that defines u is lost; we use the
definition above, which makes the third loop's formula come out right.

The last link carries nothing, so its d is the inertia of a rod about its end, mL²/3. At the
base, d₁ is the inertia that a torque at joint 1 alone meets while the outer joints swing
freely: less than the chain's inertia about hinge 1 when held rigid (M₁₁), and exactly
1/(M⁻¹)₁₁.]],
      formula = "I^accu ← I^accu + R(I_j^accu − h_j h_jᵀ/d_j)Rᵀ\n" ..
                "p^accu ← p^accu + R(p_j^accu + I_j^accu c_j + (u_j/d_j) h_j)\n" ..
                "hᵢ = I^accu sᵢ,  dᵢ = sᵢᵀ hᵢ,  uᵢ = τᵢ − hᵢᵀ cᵢ − sᵢᵀ p^accu",
      run = function(ctx)
        local art = chain()
        art:set_state(q0, qd0)
        local trace = art:aba_trace({0, 0, 0})
        ctx:say("I^accu of link 3 (its own spatial inertia: nothing hangs on it):")
        ctx:table({"ωx", "ωy", "ωz", "vx", "vy", "vz"}, trace.links[3].IA)
        ctx:expect("d₃ = mL²/3 (a rod about its end)", trace.links[3].d, m * L * L / 3, 1e-14)
        local rows = {}
        for k = 1, 3 do
          local loops = trace.links[k]
          rows[k] = {k, loops.d, loops.u}
        end
        ctx:table({"link", "d (kg·m²)", "u (N·m)"}, rows)
        -- At the base, d₁ is the inertia a torque at joint 1 alone meets when the outer
        -- joints swing freely: q̈₁ = τ₁/d₁ from rest, so d₁ = 1/(M⁻¹)₁₁.
        local M = art:mass_matrix()
        local column = solve(M, {1, 0, 0})
        ctx:expect_range("d₁ below M₁₁, the chain held rigid about hinge 1 (kg·m²)",
                         trace.links[1].d, nil, M[1][1])
        ctx:expect("d₁ = 1/(M⁻¹)₁₁ (the outer links free to swing)", trace.links[1].d,
                   1 / column[1], 1e-12)
      end,
    },
    {
      title = "Loop 3: accelerations, and the check against the mass matrix",
      text = [[
The last loop goes from the base out again. With the parent's acceleration known, the
joint's acceleration follows from the linear relation the slide starts from, f + F_ext =
I a + p: q̈ᵢ = (uᵢ − hᵢᵀ R aⱼ)/dᵢ, and the link's acceleration is aᵢ = R aⱼ + cᵢ + sᵢ q̈ᵢ.
Three passes over the links, each doing a fixed amount of work per link: O(n).

The other road to the same numbers forms the 3 × 3 mass matrix M(q) (composite rigid body
algorithm), the bias forces C(q, q̇)q̇ + g(q) (recursive Newton-Euler with q̈ = 0) and solves
M q̈ = τ − C q̇ − g. For a chain of n links that costs n³ and is what the articulated-body
algorithm avoids (bench/run times both side by side for chains of 5 to 200 links).]],
      formula = "q̈ᵢ = (uᵢ − hᵢᵀ R aⱼ) / dᵢ     aᵢ = R aⱼ + cᵢ + sᵢ q̈ᵢ",
      run = function(ctx)
        local art = chain()
        art:set_state(q0, qd0)
        local tau = {0.5, 0, -0.2}
        local trace = art:aba_trace(tau)
        for k = 1, 3 do ctx:show("a" .. k, trace.links[k].a) end
        ctx:show("q̈ from the three loops (rad/s²)", trace.qdd)
        local M, b = art:mass_matrix(), art:bias_forces()
        ctx:say("M(q):")
        ctx:table({"", "", ""}, M)
        ctx:show("C q̇ + g (N·m)", b)
        local rhs = {}
        for i = 1, 3 do rhs[i] = tau[i] - b[i] end
        ctx:expect("q̈ = M⁻¹(τ − C q̇ − g)", trace.qdd, solve(M, rhs), 1e-12)
        local a1 = trace.links[1].a
        ctx:expect("a₁ = c₁ + s₁ q̈₁ (the base does not move)", a1,
                   {0, 0, trace.qdd[1], trace.links[1].c[4], trace.links[1].c[5], 0}, 1e-14)
      end,
    },
  },
}
