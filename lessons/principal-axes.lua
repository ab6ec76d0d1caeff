-- Principal axes (002 "Principal Axes", "Diagonalization of Rotational Inertial"): every inertia
-- tensor is I = A·I₀·Aᵀ with A a rotation and I₀ diagonal; L along a principal axis gives ω ∥ L,
-- any other L does not.

-- A 6 kg box, 1 × 2 × 3 m: in its own axes I₀ = (m/12)·diag(h² + d², w² + d², w² + h²)
-- = 0.5·diag(13, 10, 5) = diag(6.5, 5, 2.5) kg·m².
local I0 = mat3.diag(6.5, 5, 2.5)
-- The box turned by 0.9 rad about (1, 2, 2): A's columns are where the box's x, y, z axes point.
local A = quat.axis_angle(vec3(1, 2, 2), 0.9):to_mat3()
local I = A * I0 * A:transpose()

-- A vector with four decimals, for tables.
local function short(v) return string.format("(%.4f, %.4f, %.4f)", v.x, v.y, v.z) end

-- Angle between two vectors (degrees).
local function angle_between(a, b)
  return math.deg(math.acos(math.max(-1, math.min(1, a:dot(b) / (a:norm() * b:norm())))))
end

return lesson{
  id = "principal-axes",
  title = "Principal axes: diagonalising the inertia tensor",
  source = "002_5497adede943f513.txt, \"Principal Axes\", " ..
           "\"Diagonalization of Rotational Inertial\"",
  steps = {
    {
      title = "A turned box has products of inertia",
      text = [[
In a box's own axes, along its edges, the inertia tensor is diagonal: I₀ = diag(6.5, 5, 2.5)
kg·m² for a 6 kg box of 1 × 2 × 3 m. Turn the box in space and describe it in the fixed x, y, z
axes, and the same body gets a full matrix with products of inertia everywhere. Nothing about
the box has changed; we are just looking at it along axes that are not its natural ones.

The slides of 002 write the relation as I = A·I₀·Aᵀ: A is the rotation that carries the
principal axes onto their current directions (its columns are where the box's edges now
point). rigidlab's inertia.rotate(I₀, A) computes the same product.]],
      formula = "I = A·I₀·Aᵀ,   I₀ = diag(I_x, I_y, I_z)",
      run = function(ctx)
        ctx:show("I₀, the box in its own axes (kg·m²)", I0)
        ctx:show("A, the box's orientation", A)
        ctx:show("I = A·I₀·Aᵀ (kg·m²)", I)
        ctx:expect("inertia.rotate(I₀, A) = A·I₀·Aᵀ", inertia.rotate(I0, A), I)
        ctx:expect("turning keeps the trace, I_x + I_y + I_z = 14", I:trace(), 14)
        ctx:expect("... and the determinant, 6.5·5·2.5 = 81.25", I:det(), 81.25)
      end,
    },
    {
      title = "Diagonalising: the eigenvalues and eigenvectors",
      text = [[
Going the other way, from a full matrix back to the principal axes, is an eigenvalue problem.
A symmetric 3×3 matrix always has three real eigenvalues and three mutually perpendicular
eigenvectors: directions e for which I·e points along e itself, I·e = λ·e. Those directions are
the principal axes and the λ are the principal moments. Given only the full matrix I,
inertia.principal(I) finds them, smallest first.

They must be the box's: 2.5 about its long edge (easiest to spin about), then 5, then 6.5
about its short edge. The axes come back as the columns of a rotation matrix; each is one of A's
columns, possibly pointing the opposite way (an axis has no preferred sign).]],
      formula = "I·eₖ = λₖ·eₖ,   I = [e₁ e₂ e₃]·diag(λ₁, λ₂, λ₃)·[e₁ e₂ e₃]ᵀ",
      run = function(ctx)
        local values, axes = inertia.principal(I)
        ctx:show("principal moments λ (kg·m²)", values)
        ctx:show("principal axes (columns)", axes)
        ctx:expect("λ = (2.5, 5, 6.5), the box's moments", values, vec3(2.5, 5, 6.5))
        local rows, moments = {}, {values:unpack()}
        for k = 1, 3 do
          local e = axes:col(k)
          local residual = (I * e - moments[k] * e):norm()
          rows[k] = {k, moments[k], short(e), residual, math.abs(e:dot(A:col(4 - k)))}
        end
        ctx:table({"k", "λₖ", "eₖ", "|I·eₖ − λₖeₖ|", "|eₖ·A column|"}, rows)
        for k = 1, 3 do
          ctx:expect("I·e" .. k .. " = λ" .. k .. "·e" .. k, rows[k][4], 0, {abs = 1e-12})
          ctx:expect("e" .. k .. " is A's column " .. (4 - k) .. " (up to sign)", rows[k][5], 1)
        end
        ctx:expect("axes form a rotation: det = +1", axes:det(), 1)
        ctx:expect("[e₁ e₂ e₃]ᵀ·I·[e₁ e₂ e₃] = diag(2.5, 5, 6.5)",
                   axes:transpose() * I * axes, mat3.diag(2.5, 5, 6.5), {abs = 1e-12})
      end,
    },
    {
      title = "When does ω point along L?",
      text = [[
Angular momentum and angular velocity are tied by L = I·ω, so ω = I⁻¹·L. If L lies along a
principal axis, ω = L/λ points the same way: the body spins steadily about that axis. If L
points anywhere else, the three components are divided by three different moments and ω
leans away from L. The slides show three such pairs and note that two of them are aligned
because they lie on principal axes.

We check with cross products: ω × L is zero exactly when the two are parallel. For L along
the box's long edge (λ = 2.5) and along its short edge (λ = 6.5) the cross product vanishes
and ω = L/λ; for L = (1, 1, 1) it does not, and ω leans away by many degrees. A body whose ω
and L disagree cannot keep spinning about a fixed line: with L fixed in space and ω moving
with the body, it tumbles.]],
      formula = "ω = I⁻¹·L;   L = λ·e (principal) ⇒ ω = L/λ ∥ L;   otherwise ω × L ≠ 0",
      run = function(ctx)
        local inverse = I:inverse()
        local cases = {
                    {"long edge (λ = 2.5)", 4 * A:col(3), 2.5},
          {"short edge (λ = 6.5)", 4 * A:col(1), 6.5},
                    {"(1, 1, 1)", vec3(1, 1, 1), nil},
        }
        local rows = {}
        for i, case in ipairs(cases) do
          local L = case[2]
          local omega = inverse * L
                    rows[i] = {case[1], short(omega), string.format("%.1e", omega:cross(L):norm()),
                     string.format("%.2f", angle_between(omega, L))}
          if case[3] then
                        ctx:expect("L along the " .. case[1] .. ": ω = L/λ", omega, L * (1 / case[3]),
                       {abs = 1e-12})
            ctx:expect("L along the " .. case[1] .. ": |ω × L| = 0", omega:cross(L):norm(), 0,
                       {abs = 1e-12})
          end
        end
        ctx:table({"L along", "ω = I⁻¹L (rad/s)", "|ω × L|", "angle (°)"}, rows)
        local generic = inverse * vec3(1, 1, 1)
        -- Independent of the inverse: in the box's axes ω is L's components divided by the moments.
        local in_box_axes = A:transpose() * vec3(1, 1, 1)
        local expected = A * vec3(in_box_axes.x / 6.5, in_box_axes.y / 5, in_box_axes.z / 2.5)
        ctx:expect("generic L: ω = A·diag(1/6.5, 1/5, 1/2.5)·Aᵀ·L", generic, expected)
        ctx:show("|ω × L| for L = (1, 1, 1)", generic:cross(vec3(1, 1, 1)):norm())
      end,
    },
  },
}
