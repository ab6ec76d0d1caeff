-- The perpendicular axis theorem (000 "Perpendicular axis theorem"): for a flat body in the
-- xy plane, I_z = I_x + I_y; for a symmetric flat body such as a thin disc, I_z = 2·I_x.

local x_axis, y_axis, z_axis = vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)

-- A flat, lopsided set of particles in the plane z = 0 (kg, m), centre of mass at the origin:
-- Σ m·x = 2 − 2 + 0 = 0,  Σ m·y = 1 + 0 − 1 = 0.
local flat_particles = {
  {mass = 1, pos = vec3(2, 1, 0)},
  {mass = 2, pos = vec3(-1, 0, 0)},
  {mass = 1, pos = vec3(0, -1, 0)},
}

return lesson{
  id = "perpendicular-axis",
  title = "The perpendicular axis theorem",
  source = "000_3bd95e59483beea1.txt, \"Perpendicular axis theorem\"",
  steps = {
    {
      title = "Flat bodies: I_z = I_x + I_y",
      text = [[
For a body that lies flat in the xy plane every piece has z = 0. Then the moment about x is
Σ m·y² (the distance from the x axis is just |y|), the moment about y is Σ m·x², and the
moment about z, the axis standing up out of the plane, is Σ m(x² + y²): exactly the sum of the
other two. No symmetry is needed, only flatness.

Our flat body has three particles: 1 kg at (2, 1), 2 kg at (−1, 0) and 1 kg at (0, −1) m,
balanced about the origin. By hand: I_x = 1·1² + 0 + 1·1² = 2, I_y = 1·2² + 2·1² + 0 = 6, so
I_z must be 8 kg·m². The rule also holds for any other pair of perpendicular axes in the plane
through the same point: turning the pair by 30° changes both moments, not their sum.]],
      formula = "I_z = I_x + I_y   (flat body in the xy plane)",
      run = function(ctx)
        local _, com, I = inertia.points(flat_particles)
        ctx:show("centre of mass (m)", com)
        ctx:show("tensor about the centre of mass (kg·m²)", I)
        ctx:expect("I_x = Σm·y² = 2, I_y = Σm·x² = 6, I_z = 8, xy entry −Σm·x·y = −2", I,
                   mat3(2, -2, 0,
                        -2, 6, 0,
                        0, 0, 8))
        local I_x, I_y, I_z = inertia.about_axis(I, x_axis), inertia.about_axis(I, y_axis),
                              inertia.about_axis(I, z_axis)
        ctx:show("I_x + I_y (kg·m²)", I_x + I_y)
        ctx:expect("I_z = I_x + I_y", I_z, I_x + I_y)
        local a = math.rad(30)
        local u, v = vec3(math.cos(a), math.sin(a), 0), vec3(-math.sin(a), math.cos(a), 0)
        local I_u, I_v = inertia.about_axis(I, u), inertia.about_axis(I, v)
        ctx:show("axes turned by 30°: I_u, I_v (kg·m²)", {I_u, I_v})
        -- n·I·n by hand for n = (cos a, sin a, 0): 2cos²a + 6sin²a + 2·(−2)·sin a·cos a
        ctx:expect("I_u = 2cos²30° + 6sin²30° − 4·sin30°·cos30°", I_u,
                   2 * math.cos(a) ^ 2 + 6 * math.sin(a) ^ 2 - 4 * math.sin(a) * math.cos(a))
        ctx:expect("I_u + I_v = I_z = 8", I_u + I_v, 8)
      end,
    },
    {
      title = "A thin disc: I_z = 2·I_x",
      text = [[
If the flat body is also round, I_x and I_y must be equal (nothing distinguishes the two
directions), so each is half of I_z. A disc of radius r has I_z = m·r²/2 about its axis, so
about any diameter I_x = m·r²/4, with no integral needed. A thin ring, all mass at r, has
I_z = m·r² and so I_x = m·r²/2.

A real disc has some thickness h, and then it is a short cylinder with
I_x = m(3r² + h²)/12: the theorem holds only as h → 0. The table shows the gap
I_z − (I_x + I_y) = −m·h²/6 closing as the disc gets thinner (m = 1.5 kg, r = 0.2 m). The
"thin" disc and ring below are 1 µm thick, which adds m·h²/12 ≈ 1e-13 kg·m² to I_x: they
are checked to 1e-12.]],
      formula = "symmetric flat body: I_z = 2·I_x = 2·I_y\n" ..
                "disc: I_x = m·r²/4,   ring: I_x = m·r²/2",
      run = function(ctx)
        local m, r = 1.5, 0.2
        local rows = {}
        for _, h in ipairs({0.1, 0.01, 0.001}) do
          local disc = inertia.solid_cylinder(m, r, h)
          local gap = disc:get(3, 3) - disc:get(1, 1) - disc:get(2, 2)
          rows[#rows + 1] = {h, disc:get(1, 1), disc:get(3, 3), gap, -m * h ^ 2 / 6}
        end
        ctx:table({"h (m)", "I_x", "I_z", "I_z − I_x − I_y", "−m·h²/6"}, rows)
        ctx:expect("gap = −m·h²/6 at h = 1 mm", rows[3][4], -m * 0.001 ^ 2 / 6)
        local disc = inertia.solid_cylinder(m, r, 1e-6)
        ctx:expect("thin disc I_z = m·r²/2 = 0.03", disc:get(3, 3), 0.03)
        ctx:expect("thin disc I_x = I_z/2 = m·r²/4 = 0.015", disc:get(1, 1), 0.015, {abs = 1e-12})
        local ring = inertia.hollow_cylinder(m, r, 1e-6)
        ctx:show("thin ring (kg·m²)", ring)
        ctx:expect("thin ring I_x = I_z/2 = m·r²/2 = 0.03", {ring:get(1, 1), ring:get(3, 3)},
                   {0.03, 0.06}, {abs = 1e-12})
      end,
    },
    {
      title = "Only flat bodies: a cube breaks it",
      text = [[
For a body with thickness every piece adds z² to both I_x and I_y but nothing to I_z, so in
general I_x + I_y = I_z + 2·Σ m·z² ≥ I_z. Equality is the signature of flatness. A thin plate
of w × h (a box with tiny depth) obeys I_z = I_x + I_y = m(w² + h²)/12; a cube of side a, with
every moment m·a²/6, has I_x + I_y = m·a²/3, twice its I_z. We take a 2 kg plate of
0.4 × 0.3 m, 1 µm deep, and a 2 kg cube of side 0.3 m. This inequality between the three
moments holds for every rigid body, about any point and in any orientation: a tensor that
breaks it cannot belong to anything real, and body{} refuses it.]],
      formula = "any body: I_x + I_y = I_z + 2·∫z² dm ≥ I_z",
      run = function(ctx)
        local m, w, h = 2, 0.4, 0.3
        local plate = inertia.solid_box(m, w, h, 1e-6)
        ctx:expect("plate: I_z = m(w² + h²)/12 = 2·0.25/12", plate:get(3, 3), 2 * 0.25 / 12)
        ctx:expect("plate: I_x + I_y = I_z (up to m·d²/6 = 3e-13)",
                   plate:get(1, 1) + plate:get(2, 2), plate:get(3, 3), {abs = 1e-12})
        local a = 0.3
        local cube = inertia.solid_box(m, a, a, a)
        ctx:show("cube of side 0.3 m (kg·m²)", cube)
        local excess = cube:get(1, 1) + cube:get(2, 2) - cube:get(3, 3)
        ctx:show("cube: I_x + I_y − I_z = 2·∫z² dm (kg·m²)", excess)
        ctx:expect("cube: 2·∫z² dm = 2·m·a²/12 = 0.03", excess, 2 * m * a ^ 2 / 12)
        local ok, message = pcall(body, {mass = 1, inertia = mat3.diag(1, 1, 3)})
                ctx:say("body{mass = 1, inertia = mat3.diag(1, 1, 3)} → " .. (ok and "accepted" or "refused:"))
        if not ok then   -- the message, broken into lines of at most 74 characters
          local line = ""
          for word in message:gmatch("%S+") do
            if #line > 0 and utf8.len(line) + 1 + utf8.len(word) > 74 then
              ctx:say("  " .. line)
              line = word
            else
              line = #line > 0 and line .. " " .. word or word
            end
          end
          ctx:say("  " .. line)
        end
        ctx:expect("a tensor with I_x + I_y < I_z is refused", ok and 1 or 0, 0)
      end,
    },
  },
}
