-- The parallel axis theorem (000 "Parallel axis theorem"): I_v = I_com + m·d² for a scalar
-- moment, and I_P = I_com + m((d·d)E − d⊗d) for the whole tensor, products of inertia included.

local x_axis = vec3(1, 0, 0)

-- A thin rod: a solid cylinder of 1.2 kg, 2 m long, 1 cm in radius, along z.
local rod_mass, rod_length, rod_radius = 1.2, 2, 0.01

-- The rod as n equal particles at the middles of n equal pieces, summed about its end z = 0:
-- Σ (m/n)·zₖ² with zₖ = (k − ½)L/n. Exactly mL²/3·(1 − 1/(4n²)).
local function rod_by_particles(n)
  local total = 0
  for k = 1, n do
    total = total + rod_mass / n * ((k - 0.5) * rod_length / n) ^ 2
  end
  return total
end

return lesson{
  id = "parallel-axis",
  title = "The parallel axis theorem",
  source = "000_3bd95e59483beea1.txt, \"Parallel axis theorem\"",
  steps = {
    {
      title = "A rod turned about its end",
      text = [[
The tables give each shape's inertia about its centre of mass, but things often turn about
some other point: a door about its hinges, a pendulum about its pivot, a bat about the
hands. The parallel axis theorem moves the axis without redoing any integral: about a line
parallel to one through the centre of mass, at distance d from it, I_v = I_com + m·d².
The extra m·d² is what the whole mass would contribute if it sat at the centre of mass; the
I_com part is the spread of the mass around that centre, which does not change.

A rod of length L = 2 m and mass 1.2 kg about its middle has I = mL²/12 = 0.4 kg·m² (plus a
tiny m·3r²/12 from its 1 cm thickness). About its end, d = L/2 = 1 m, so
I = mL²/12 + m(L/2)² = mL²/3 = 1.6 kg·m², four times as much: a rod is much harder to swing
from its end than to twirl about its middle. As an independent check we chop the rod into n
equal particles and add m·z² about the end; the sum is exactly (mL²/3)(1 − 1/(4n²)).]],
      formula = "I_v = I_com + m·d²;   rod: mL²/12 + m(L/2)² = mL²/3",
      run = function(ctx)
        local I_com = inertia.solid_cylinder(rod_mass, rod_radius, rod_length)
        ctx:show("rod about its centre of mass (kg·m²)", I_com)
        ctx:expect("I_com about x = m(3r² + L²)/12", inertia.about_axis(I_com, x_axis),
                   rod_mass * (3 * rod_radius ^ 2 + rod_length ^ 2) / 12)
        -- the end is at z = 0, the COM at z = L/2: d = COM − end
        local d = vec3(0, 0, rod_length / 2)
        local I_end = inertia.parallel_axis(I_com, rod_mass, d)
        ctx:show("d = COM − end (m)", d)
        ctx:show("rod about its end (kg·m²)", I_end)
        local about_end = inertia.about_axis(I_end, x_axis)
        ctx:expect("about the end: m(3r² + L²)/12 + m(L/2)²", about_end,
                   rod_mass * (3 * rod_radius ^ 2 + rod_length ^ 2) / 12 + rod_mass * 1 ^ 2)
        ctx:show("mL²/3 for an ideal thin rod (kg·m²)", rod_mass * rod_length ^ 2 / 3)
        ctx:show("the rod's thickness adds m·r²/4 (kg·m²)",
                 about_end - rod_mass * rod_length ^ 2 / 3)
        ctx:expect("thin-rod value mL²/3 = 1.6, up to the thickness term m·r²/4 = 3e-5",
                   about_end, 1.6, {abs = 3.1e-5})
        local rows = {}
        for _, n in ipairs({1, 10, 100, 1000}) do
          rows[#rows + 1] = {n, rod_by_particles(n), 1.6 - rod_by_particles(n)}
        end
        ctx:table({"particles n", "Σ (m/n)·zₖ² (kg·m²)", "1.6 − sum"}, rows)
        ctx:expect("1000 particles: (mL²/3)(1 − 1/(4·1000²))", rod_by_particles(1000),
                   1.6 * (1 - 1 / 4e6))
      end,
    },
    {
      title = "The smallest moment is through the centre of mass",
      text = [[
Since m·d² is never negative, among all parallel axes the one through the centre of mass has
the smallest moment. A ball shows it well. A solid ball of 2 kg and radius 0.1 m spinning
about its centre has (2/5)mr² = 0.008 kg·m². A ball rolling on the floor turns, at each
instant, about the line where it touches the floor, at distance r from its centre:
(2/5)mr² + mr² = (7/5)mr² = 0.028 kg·m². That 7/5 is why a rolling ball accelerates down a
slope more slowly than a sliding block: part of the work goes into spinning it.]],
      formula = "I_contact = (2/5)mr² + m·r² = (7/5)·m·r²",
      run = function(ctx)
        local m, r = 2, 0.1
        local I_com = inertia.solid_sphere(m, r)
        -- contact point under the ball: COM − contact = (0, r, 0)
        local I_contact = inertia.parallel_axis(I_com, m, vec3(0, r, 0))
        ctx:show("about the centre (kg·m²)", I_com)
        ctx:show("about the contact point (kg·m²)", I_contact)
        ctx:expect("rolling axis (x, through the contact): (7/5)·2·0.1² = 0.028",
                   inertia.about_axis(I_contact, x_axis), 0.028)
        ctx:expect("vertical axis through the contact: still (2/5)mr² (d is along it)",
                   inertia.about_axis(I_contact, vec3(0, 1, 0)), 0.008)
      end,
    },
    {
      title = "The tensor form: a box about its corner",
      text = [[
For the whole tensor the shift is I_P = I_com + m((d·d)E − d⊗d): the same matrix as a single
particle of the body's whole mass sitting at offset d. Its diagonal adds m(d_y² + d_z²) to
I_xx and so on (the squared distance of the centre from each axis), and it brings products of
inertia −m·dₓ·d_y ... where the centred body had none.

Take a box of 2 kg, 1 × 0.5 × 0.25 m, about one corner: d = (0.5, 0.25, 0.125) m from that
corner to the centre. An independent answer comes from integrating over the box with the
corner as origin, x from 0 to w and so on: the mean of x² is w²/3 and the mean of x·y is
w·h/4, so I_xx = m(h² + d²)/3 and the xy product is −m·w·h/4.

A slip in 000: the slide writes I_xx = ∫(y² + z²)dm + m·dₓ². A shift along x does not move
the mass away from the x axis at all; what counts are the other two components:
I_xx = ∫(y² + z²)dm + m(d_y² + d_z²). For our box the printed version gives 0.552 kg·m² instead
of 0.208. (Its products, I_xy = ∫xy dm + m·dₓd_y, are right in its own convention, in which
the tensor holds −I_xy.)]],
      formula = "I_P = I_com + m((d·d)E − d⊗d):\n" ..
                "  I_xx += m(d_y² + d_z²),  I_yy += m(dₓ² + d_z²),  I_zz += m(dₓ² + d_y²)\n" ..
                "  entries xy −= m·dₓ·d_y,  xz −= m·dₓ·d_z,  yz −= m·d_y·d_z",
      run = function(ctx)
        local m, w, h, depth = 2, 1, 0.5, 0.25
        local I_com = inertia.solid_box(m, w, h, depth)
        local d = vec3(w / 2, h / 2, depth / 2)
        ctx:show("box about its centre (kg·m²)", I_com)
        ctx:show("d = centre − corner (m)", d)
        local I_corner = inertia.parallel_axis(I_com, m, d)
        ctx:show("box about its corner, parallel_axis (kg·m²)", I_corner)
        local by_integration = m * mat3((h ^ 2 + depth ^ 2) / 3, -w * h / 4, -w * depth / 4,
                                        -w * h / 4, (w ^ 2 + depth ^ 2) / 3, -h * depth / 4,
                                        -w * depth / 4, -h * depth / 4, (w ^ 2 + h ^ 2) / 3)
        ctx:show("integrated over the box from its corner (kg·m²)", by_integration)
        ctx:expect("parallel axis = direct integral about the corner", I_corner, by_integration)
        ctx:expect("the corner tensor in numbers", I_corner,
                   mat3(0.625 / 3, -0.25, -0.125,
                        -0.25, 2.125 / 3, -0.0625,
                        -0.125, -0.0625, 2.5 / 3))
        local as_printed = I_com:get(1, 1) + m * d.x ^ 2
        ctx:show("I_xx as printed in 000, ∫(y²+z²)dm + m·dₓ² (wrong)", as_printed)
        ctx:show("I_xx = ∫(y²+z²)dm + m(d_y² + d_z²) (right)",
                 I_com:get(1, 1) + m * (d.y ^ 2 + d.z ^ 2))
        ctx:expect("engine I_xx is the right one", I_corner:get(1, 1),
                   I_com:get(1, 1) + m * (d.y ^ 2 + d.z ^ 2))
      end,
    },
  },
}
