-- A body built from primitive shapes (000 "Complex objects"): a dumbbell of two balls on a rod.
-- 1. each part's inertia about its own centre, 2. the parallel axis shift to the common centre
-- of mass, 3. the sum.

-- The parts (kg, m): a rod along z from z = −0.25 to 0.25, a heavy ball on top touching its end,
-- a lighter, smaller ball below.
local rod = {mass = 0.5, radius = 0.02, length = 0.5, center = vec3(0, 0, 0)}
local top = {mass = 3, radius = 0.1, center = vec3(0, 0, 0.35)}
local bottom = {mass = 2, radius = 0.08, center = vec3(0, 0, -0.33)}
local total_mass = 5.5
local com_z = (3 * 0.35 + 2 * -0.33 + 0.5 * 0) / 5.5   -- = 0.39/5.5 m

-- Each part's tensor about its own centre from the table in 000, written out.
local function ball_by_formula(part)
  return mat3.diag(1, 1, 1) * (2 / 5 * part.mass * part.radius ^ 2)
end
local rod_by_formula = mat3.diag(rod.mass * (3 * rod.radius ^ 2 + rod.length ^ 2) / 12,
                                 rod.mass * (3 * rod.radius ^ 2 + rod.length ^ 2) / 12,
                                 rod.mass * rod.radius ^ 2 / 2)

-- The dumbbell's moments about its centre of mass, summed by hand: about x (and y) each part's
-- own moment plus m·d² with d its centre's height above the common centre; about z (the bar)
-- the parts' own moments only, all the offsets being along z.
local function hand_sum()
  local about_x = 0
  for _, p in ipairs({{top, ball_by_formula(top)}, {bottom, ball_by_formula(bottom)},
                      {rod, rod_by_formula}}) do
    about_x = about_x + p[2]:get(1, 1) + p[1].mass * (p[1].center.z - com_z) ^ 2
  end
  local about_z = ball_by_formula(top):get(3, 3) + ball_by_formula(bottom):get(3, 3) +
                  rod_by_formula:get(3, 3)
  return about_x, about_z
end

-- The parts as inertia.composite takes them: engine tensors, axes of the dumbbell's frame.
local function parts()
  return {
    {mass = top.mass, com = top.center, inertia = inertia.solid_sphere(top.mass, top.radius)},
    {mass = bottom.mass, com = bottom.center,
     inertia = inertia.solid_sphere(bottom.mass, bottom.radius)},
    {mass = rod.mass, com = rod.center,
     inertia = inertia.solid_cylinder(rod.mass, rod.radius, rod.length)},
  }
end

return lesson{
  id = "composite",
  title = "A composite body: the dumbbell",
  source = "000_3bd95e59483beea1.txt, \"Complex objects\"",
  steps = {
    {
      title = "1. Each part about its own centre",
      text = [[
Few real objects are a single primitive shape, but many are a handful of them stuck together.
The recipe in 000 has three steps, and this lesson takes them one at a time on a dumbbell: a
rod 0.5 m long (0.5 kg, radius 2 cm) along z, a 3 kg ball of radius 10 cm on its top end and a
2 kg ball of radius 8 cm on its bottom end. First each part's tensor about its own centre,
straight from the table: (2/5)m·r² for the balls, m(3r² + L²)/12 and m·r²/2 for the rod.]],
      formula = "ball: (2/5)·m·r²·E;   rod: diag(m(3r² + L²)/12, m(3r² + L²)/12, m·r²/2)",
      run = function(ctx)
        for _, part in ipairs({{"top ball", top}, {"bottom ball", bottom}}) do
          local engine = inertia.solid_sphere(part[2].mass, part[2].radius)
          ctx:show(part[1] .. " about its centre (kg·m²)", engine)
          ctx:expect(part[1] .. " = (2/5)m·r²·E", engine, ball_by_formula(part[2]))
        end
        ctx:expect("top ball: (2/5)·3·0.1² = 0.012", inertia.solid_sphere(3, 0.1):get(1, 1), 0.012)
        local engine_rod = inertia.solid_cylinder(rod.mass, rod.radius, rod.length)
        ctx:show("rod about its centre (kg·m²)", engine_rod)
        ctx:expect("rod = diag(m(3r² + L²)/12, same, m·r²/2)", engine_rod, rod_by_formula)
      end,
    },
    {
      title = "2. The common centre of mass and the shifts",
      text = [[
The parts must all be referred to one point, the dumbbell's centre of mass, the mass-weighted
average of the parts' centres: (3·0.35 + 2·(−0.33) + 0.5·0)/5.5 = 0.39/5.5 ≈ 0.0709 m up the
rod, pulled toward the heavier ball. Each part's tensor then moves there with the parallel axis
theorem, I + m((d·d)E − d⊗d) with d the offset of the part's centre from the common one.

Notice in the table how the shifts dwarf the parts' own moments about x: the balls are small,
but they sit far from the middle. That is why a dumbbell is so hard to swing end over end
compared with twirling it about its own bar (about z the shift adds nothing, all the offsets
being along z).]],
      formula = "x_com = Σ mᵢ·cᵢ / Σ mᵢ\n" ..
                "Iᵢ' = Iᵢ + mᵢ((dᵢ·dᵢ)E − dᵢ⊗dᵢ),  dᵢ = cᵢ − x_com",
      run = function(ctx)
        local com = vec3(0, 0, com_z)
        ctx:show("centre of mass by hand (m)", com)
        local rows = {}
        for _, part in ipairs({{"top ball", top, ball_by_formula(top)},
                               {"bottom ball", bottom, ball_by_formula(bottom)},
                               {"rod", rod, rod_by_formula}}) do
          local p = part[2]
          local d = p.center - com
          local shifted = inertia.parallel_axis(part[3], p.mass, d)
          -- d is along z, so the shift adds m·d_z² to I_xx and I_yy and nothing to I_zz
          local by_hand = part[3] + mat3.diag(p.mass * d.z ^ 2, p.mass * d.z ^ 2, 0)
          ctx:expect(part[1] .. ": parallel_axis = I + diag(m·d², m·d², 0)", shifted, by_hand)
          rows[#rows + 1] = {part[1], d.z, part[3]:get(1, 1), p.mass * d.z ^ 2, shifted:get(1, 1)}
        end
        ctx:table({"part", "d_z (m)", "own I_xx", "m·d²", "shifted I_xx"}, rows)
      end,
    },
    {
      title = "3. The sum",
      text = [[
The last step adds the shifted tensors. rigidlab's inertia.composite does all three steps at
once from a list of parts (each with its mass, centre and own tensor) and returns the total
mass, the centre of mass and the tensor about it. We check it against the hand sum, and against
a second route: add every part about the origin (shifting by its centre cᵢ), then move the
total to the centre of mass with the theorem backwards, subtracting M·x_com². Both routes meet.]],
      formula = "I = Σᵢ [Iᵢ + mᵢ((dᵢ·dᵢ)E − dᵢ⊗dᵢ)]\n" ..
                "  = Σᵢ [Iᵢ + mᵢ·cᵢ²] − M·x_com²   (about x and y)",
      run = function(ctx)
        local mass, com, I = inertia.composite(parts())
        ctx:show("total mass (kg)", mass)
        ctx:show("centre of mass (m)", com)
        ctx:show("dumbbell tensor about its centre of mass (kg·m²)", I)
        ctx:expect("mass = 3 + 2 + 0.5", mass, total_mass)
        ctx:expect("centre of mass = (0, 0, 0.39/5.5)", com, vec3(0, 0, 0.39 / 5.5))
        local about_x, about_z = hand_sum()
        ctx:expect("hand sum: diag(Σ(Iᵢ + mᵢdᵢ²), same, Σ Iᵢ)", I,
                   mat3.diag(about_x, about_x, about_z))
        local origin_route = 0.012 + 3 * 0.35 ^ 2 + 0.00512 + 2 * 0.33 ^ 2 +
                             rod_by_formula:get(1, 1) - total_mass * com_z ^ 2
        ctx:expect("second route: Σ(Iᵢ + mᵢcᵢ²) − M·x_com²", I:get(1, 1), origin_route)
        ctx:expect("about the bar: 0.012 + 0.00512 + 0.5·0.02²/2", I:get(3, 3),
                   0.012 + 0.00512 + 0.0001)
      end,
    },
    {
      title = "Parts must share the body's axes",
      text = [[
One trap: each part's tensor has to be written in the axes of the whole body. Lay the same
dumbbell along x instead of z. The table's cylinder formula has its axis along z, so the rod's
tensor first has to be turned to lie along x, with inertia.rotate(I, R) = R·I·Rᵀ, R the quarter
turn about y that carries z onto x. (The balls look the same in every direction.) Done right,
the new body's moments are the old ones relabelled: about x it now spins on its bar, about z
it tumbles end over end.]],
      formula = "I_part in the body's axes = R·I_part·Rᵀ",
      run = function(ctx)
        local quarter_turn = quat.axis_angle(vec3(0, 1, 0), math.pi / 2)
        ctx:expect("the quarter turn about y carries z onto x", quarter_turn:rotate(vec3(0, 0, 1)),
                   vec3(1, 0, 0))
        local along_x = {}
        for i, part in ipairs(parts()) do
          along_x[i] = {mass = part.mass, com = quarter_turn:rotate(part.com),
                        inertia = inertia.rotate(part.inertia, quarter_turn)}
        end
        ctx:show("rod's tensor turned to lie along x (kg·m²)", along_x[3].inertia)
        ctx:expect("turned rod = diag(m·r²/2, m(3r² + L²)/12, m(3r² + L²)/12)", along_x[3].inertia,
                   mat3.diag(rod_by_formula:get(3, 3), rod_by_formula:get(1, 1),
                             rod_by_formula:get(1, 1)), {abs = 1e-15})
        local _, com, I = inertia.composite(along_x)
        local about_x, about_z = hand_sum()
        ctx:show("dumbbell along x: centre of mass (m)", com)
        ctx:show("dumbbell along x: tensor (kg·m²)", I)
        ctx:expect("centre of mass = (0.39/5.5, 0, 0)", com, vec3(0.39 / 5.5, 0, 0))
        ctx:expect("the hand sums relabelled: diag(bar, end over end, end over end)", I,
                   mat3.diag(about_z, about_x, about_x), {abs = 1e-15})
      end,
    },
  },
}
