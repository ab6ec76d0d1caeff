-- Mass properties of a closed triangle mesh (002 "Mirtich-Eberly Algorithm"): volume, centre of
-- mass and inertia tensor, exact for any polyhedron; a box mesh against the box formula, the
-- unit corner tetrahedron against its known integrals, then re-centring and diagonalising.

-- A box mesh: corners `low` and `low + size`, 8 vertices, 12 triangles counter-clockwise seen
-- from outside. Vertex k + 1 has offset (x, y, z) ∈ {0, 1}³ with k = x + 2y + 4z.
local function box_mesh(low, size)
  local vertices = {}
  for k = 0, 7 do
    vertices[k + 1] = low + vec3(k % 2 * size.x, (k // 2) % 2 * size.y, (k // 4) * size.z)
  end
  -- each face as a quad, corners counter-clockwise seen from outside (0-based k)
  local quads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}
  local triangles = {}
  for _, q in ipairs(quads) do
    triangles[#triangles + 1] = {q[1] + 1, q[2] + 1, q[3] + 1}
    triangles[#triangles + 1] = {q[1] + 1, q[3] + 1, q[4] + 1}
  end
  return vertices, triangles
end

-- The tetrahedron with corners at the origin and on the three unit axes.
local tetra_vertices = {vec3(0, 0, 0), vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1)}
local tetra_triangles = {{1, 3, 2}, {1, 2, 4}, {1, 4, 3}, {2, 3, 4}}

return lesson{
  id = "mesh-inertia",
  title = "Inertia of a triangle mesh",
  source = "002_5497adede943f513.txt, \"Mirtich-Eberly Algorithm\", \"Rigid Body Set-Up\"",
  steps = {
    {
      title = "A box given as a mesh",
      text = [[
Game objects usually arrive as triangle meshes, not as spheres and boxes. Mirtich (1996) found
how to get the exact volume, centre of mass and all six inertia integrals of any closed
polyhedron, and Eberly (2002) streamlined it for triangles: the divergence theorem turns each
volume integral into a sum over the surface, and each triangle adds a few products of its
corner coordinates. No sampling, no approximation: a polyhedron's integrals are polynomials.

The mesh must be closed, with every triangle's corners counter-clockwise when seen from outside,
so the algorithm knows which side is solid. First a test where we know the answer: a box
2 × 1 × 0.5 m of density 800 kg/m³, with one corner at (1, −2, 0.5), made of 12 triangles.
It must give the mass ρ·V = 800 kg, the centre at corner + half the size, (2, −1.5, 0.75),
and about that centre the box formula m/12·(h² + d², w² + d², w² + h²).]],
      formula = "m = ρ∫dV,   c = (1/V)∫r dV,\n" ..
                "I = ρ∫((r − c)·(r − c)E − (r − c)⊗(r − c)) dV",
      run = function(ctx)
        local vertices, triangles = box_mesh(vec3(1, -2, 0.5), vec3(2, 1, 0.5))
        ctx:show("triangles", #triangles)
        local mass, com, I, volume = inertia.mesh(vertices, triangles, 800)
        ctx:show("volume (m³)", volume)
        ctx:show("mass (kg)", mass)
        ctx:show("centre of mass (m)", com)
        ctx:show("inertia about the centre of mass (kg·m²)", I)
        ctx:expect("volume = 2·1·0.5", volume, 1)
        ctx:expect("mass = 800·1", mass, 800)
        ctx:expect("centre = (1 + 1, −2 + 0.5, 0.5 + 0.25)", com, vec3(2, -1.5, 0.75))
        ctx:expect("box formula: (800/12)·diag(1² + 0.5², 2² + 0.5², 2² + 1²)", I,
                   mat3.diag(800 / 12 * 1.25, 800 / 12 * 4.25, 800 / 12 * 5))
        local _, _, light = inertia.mesh(vertices, triangles)
        ctx:expect("density 1 (the default): 800 times less", light * 800, I)
      end,
    },
    {
      title = "A tetrahedron",
      text = [[
Now a shape whose tensor is not in the tables: the corner tetrahedron with vertices at the
origin and at the tips of the three unit axes. Its numbers are classical. Volume: 1/6 of the
unit cube. Centre of mass: the average of the four corners, (1/4, 1/4, 1/4). And the integrals
over it (density 1) are ∫x² dV = 1/60 and ∫xy dV = 1/120 (from the formula
∫xᵃyᵇzᶜ dV = a!·b!·c!/(a + b + c + 3)! over this simplex).

So about the origin I_xx = ∫(y² + z²) = 2/60 = 1/30 and the xy entry is −1/120. The engine
returns the tensor about the centre of mass; moving from the origin to the centre removes
m((c·c)E − c⊗c) with m = 1/6, c·c = 3/16: the diagonal drops by (1/6)(3/16 − 1/16) = 1/48,
to 1/30 − 1/48 = 1/80, and each product entry rises by (1/6)(1/16) = 1/96, to
−1/120 + 1/96 = +1/480. The centred tensor has positive products: measured from its own centre,
points far out along x tend to lie low in y (the slanted face x + y + z = 1 cuts them off), so
the x and y offsets mostly have opposite signs and −∫xy dm comes out positive.]],
      formula = "V = 1/6,  c = (1/4, 1/4, 1/4),  ∫x² dV = 1/60,  ∫xy dV = 1/120\n" ..
                "I_origin = [1/30, −1/120, −1/120; ...]\n" ..
                "I_com = I_origin − m((c·c)E − c⊗c)\n" ..
                "      = [1/80, 1/480, 1/480; 1/480, 1/80, 1/480; 1/480, 1/480, 1/80]",
      run = function(ctx)
        local mass, com, I, volume = inertia.mesh(tetra_vertices, tetra_triangles)
        ctx:show("volume (m³)", volume)
        ctx:show("centre of mass (m)", com)
        ctx:show("inertia about the centre of mass (density 1)", I)
        ctx:expect("volume = 1/6", volume, 1 / 6)
        ctx:expect("mass = 1/6 (density 1)", mass, 1 / 6)
        ctx:expect("centre = (1/4, 1/4, 1/4)", com, vec3(0.25, 0.25, 0.25))
        local p = 1 / 480
        ctx:expect("I_com = [1/80, 1/480, 1/480; ...]", I,
                   mat3(1 / 80, p, p,
                        p, 1 / 80, p,
                        p, p, 1 / 80), {abs = 1e-15})
        local about_origin = inertia.parallel_axis(I, mass, com)
        ctx:show("shifted back to the origin (d = c − 0)", about_origin)
        local q = -1 / 120
        ctx:expect("about the origin: [1/30, −1/120, −1/120; ...] from ∫x² and ∫xy",
                   about_origin, mat3(1 / 30, q, q,
                                      q, 1 / 30, q,
                                      q, q, 1 / 30), {abs = 1e-15})
      end,
    },
    {
      title = "Re-centre and diagonalise",
      text = [[
The slides' recipe for an arbitrary mesh: compute its properties, move the mesh so its centre
of mass sits at the origin, then turn it so its principal axes point along x, y and z. After
that the body is described by four numbers, the mass and three principal moments, exactly as
a simulation wants it.

For the tetrahedron the principal axes follow from its symmetry: the line through the square
corner at the origin and the centre, along (1, 1, 1)/√3, and any two directions across it. On that
line the moment is 1/80 + 2·(1/480) = 1/60; across it, 1/80 − 1/480 = 1/96 twice. We move every
vertex to v' = Aᵀ(v − c), with A the principal axes, and compute the mesh again: its centre
is now the origin and its tensor diagonal.]],
      formula = "v' = Aᵀ·(v − c)  ⇒  c' = 0,  I' = Aᵀ·I·A = diag(λ₁, λ₂, λ₃)",
      run = function(ctx)
        local _, com, I = inertia.mesh(tetra_vertices, tetra_triangles)
        local values, axes = inertia.principal(I)
        ctx:show("principal moments (density 1)", values)
        ctx:show("principal axes (columns)", axes)
        ctx:expect("principal moments (1/96, 1/96, 1/60)", values, vec3(1 / 96, 1 / 96, 1 / 60),
                   {abs = 1e-15})
        ctx:expect("the 1/60 axis is along (1, 1, 1)/√3 (up to sign)",
                   math.abs(axes:col(3):dot(vec3(1, 1, 1):normalized())), 1)
        local moved = {}
        for i, v in ipairs(tetra_vertices) do
          moved[i] = axes:transpose() * (v - com)
          ctx:show("vertex " .. i .. " moved to", moved[i])
        end
        local mass, new_com, new_I, volume = inertia.mesh(moved, tetra_triangles)
        ctx:show("new centre of mass", new_com)
        ctx:show("new tensor", new_I)
        ctx:expect("centre now at the origin", new_com, vec3(0, 0, 0), {abs = 1e-15})
        ctx:expect("tensor now diag(1/96, 1/96, 1/60)", new_I, mat3.diag(1 / 96, 1 / 96, 1 / 60),
                   {abs = 1e-15})
        ctx:expect("mass and volume unchanged", {mass, volume}, {1 / 6, 1 / 6})
      end,
    },
  },
}
