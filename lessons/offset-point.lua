-- Velocity and acceleration of a point fixed on a rotating body (004 "Example: Circular
-- Movement", "Example: Rotation around Axis"; 002 "Kinematics of Offset Points").

local z_axis = vec3(0, 0, 1)

-- 004's 2D circle, written out in components: position, velocity and acceleration of a point
-- at radius r and angle φ turning at ω with angular acceleration α.
local function circle(r, phi, omega, alpha)
  local radial = vec3(math.cos(phi), math.sin(phi), 0)        -- (cos φ, sin φ)
  local tangent = vec3(-math.sin(phi), math.cos(phi), 0)      -- (−sin φ, cos φ)
  return {
    position = radial * r,
    velocity = tangent * (r * omega),
    tangential = tangent * (r * alpha),
    centripetal = vec3() - radial * (r * omega * omega),   -- (0 − …: no -0 printed)
  }
end

-- A body turning about a principal axis (z of a box) with no torque keeps ω constant; its
-- centre is pushed by a constant force.
local box_size = vec3(0.4, 0.6, 0.2)
local body_mass = 3
local push = vec3(0, 0, 6)          -- N ⇒ a_cm = (0, 0, 2) m/s²
local spin = vec3(0, 0, 3)          -- rad/s
local twist = vec3(0, 0, 0.26)      -- N·m about z; Izz = m(w² + h²)/12 = 0.13 kg·m² ⇒ α = 2 rad/s²
local point_local = vec3(0.2, 0.3, 0.1)   -- m, a corner of the box, in body coordinates

local function spinning_box()
  return body.box{mass = body_mass, size = box_size, position = vec3(1, 2, 0),
                  velocity = vec3(0.5, 0, 0), angular_velocity = spin}
end

return lesson{
  id = "offset-point",
  title = "How a point on a spinning body moves",
  source = "004_8f5d2bfd6f0c2787.txt, \"Example: Circular Movement\", \"Example: Rotation " ..
           "around Axis\"; 002_5497adede943f513.txt, \"Kinematics of Offset Points\"",
  steps = {
    {
      title = "Circular movement in components",
      text = [[
A point going round a circle of radius r at angle φ sits at r·(cos φ, sin φ). Differentiate
and you get its velocity, r·ω·(−sin φ, cos φ): along the tangent, so always perpendicular
to the radius (their dot product is r²ω(−sin φ cos φ + sin φ cos φ) = 0), with speed r·ω.
Differentiate again and the acceleration splits in two. One part, r·α along the tangent,
is there only while the spin speeds up or slows down. The other, r·ω² pointing at the
centre, is there whenever the point goes round at all: it is what bends the path into a
circle.

004 then notes that in 3D the same vectors come out of cross products with the angular
velocity vector ω⃗ (along the axis): v = ω⃗ × r, a_∥ = α⃗ × r, a_⊥ = ω⃗ × (ω⃗ × r). We take
r = 2 m, φ = 30°, ω = 3 rad/s, α = 0.5 rad/s² and compare the two ways.]],
      formula = "v = rω(−sin φ, cos φ) = ω⃗ × r\n" ..
                "a = rα(−sin φ, cos φ) − rω²(cos φ, sin φ) = α⃗ × r + ω⃗ × (ω⃗ × r)",
      run = function(ctx)
        local r, phi, omega, alpha = 2, math.pi / 6, 3, 0.5
        local by_components = circle(r, phi, omega, alpha)
        local radius_vector = by_components.position
        local omega_vector, alpha_vector = z_axis * omega, z_axis * alpha
        local velocity = omega_vector:cross(radius_vector)
        local tangential = alpha_vector:cross(radius_vector)
        local centripetal = omega_vector:cross(omega_vector:cross(radius_vector))
        ctx:show("r (m)", radius_vector)
        ctx:show("ω⃗ × r (m/s)", velocity)
        ctx:show("α⃗ × r (m/s²)", tangential)
        ctx:show("ω⃗ × (ω⃗ × r) (m/s²)", centripetal)
        ctx:expect("v = rω(−sin φ, cos φ)", velocity, by_components.velocity, 1e-12)
        ctx:expect("a_∥ = rα(−sin φ, cos φ)", tangential, by_components.tangential, 1e-12)
        ctx:expect("a_⊥ = −rω²(cos φ, sin φ)", centripetal, by_components.centripetal, 1e-12)
        ctx:expect("v ⟂ r", velocity:dot(radius_vector), 0, {abs = 1e-12})
        ctx:expect("speed = r·ω = 6 m/s", velocity:norm(), 6, 1e-12)
        ctx:expect("centripetal acceleration r·ω² = 18 m/s², toward the centre",
                   centripetal:dot(radius_vector:normalized()), -18, 1e-12)
      end,
    },
    {
      title = "Any axis, any point",
      text = [[
For a rotation about an axis through the origin, a point need not lie in the plane of its
circle: it may sit some way up the axis. Only its distance from the axis matters, the part
r⊥ of r perpendicular to ω⃗, and the cross product takes care of that by itself, because
ω⃗ × r ignores the part of r along ω⃗. So the speed is ω·r⊥, not ω·‖r‖: a point 1 m up the
axis of a turntable does not move faster than the point directly below it.]],
      formula = "ω⃗ × r = ω⃗ × r⊥,   ‖ω⃗ × r‖ = ω·r⊥",
      run = function(ctx)
        local omega_vector = vec3(1, 2, 2)         -- 3 rad/s about (1, 2, 2)/3
        local r = vec3(2, 0, 1)
        local axis = omega_vector:normalized()
        local along = axis * r:dot(axis)
        local perpendicular = r - along
        ctx:show("r along the axis (m)", along)
        ctx:show("r⊥ (m)", perpendicular)
        ctx:show("ω⃗ × r (m/s)", omega_vector:cross(r))
        ctx:show("ω⃗ × r⊥ (m/s)", omega_vector:cross(perpendicular))
        ctx:expect("ω⃗ × r = ω⃗ × r⊥", omega_vector:cross(r), omega_vector:cross(perpendicular),
                   1e-12)
        -- r·axis = (2 + 2)/3 = 4/3, so r⊥² = ‖r‖² − 16/9 = 5 − 16/9 = 29/9.
        ctx:expect("speed = ω·r⊥ = 3·√29/3 = √29", omega_vector:cross(r):norm(), math.sqrt(29),
                   1e-12)
      end,
    },
    {
      title = "A point on a moving, spinning body",
      text = [[
A rigid body usually does both at once: its centre of mass travels and the body turns about
it. 002 adds the two motions. A point fixed on the body, at offset r from the centre of
mass (in world coordinates), is at x = x_cm + r; since r only turns, its velocity is
v = v_cm + ω⃗ × r; and its acceleration is a = a_cm + α⃗ × r + ω⃗ × (ω⃗ × r).

(002 writes the angular acceleration as ω with a bar over it, defined in its "Rigid Body
Dynamics" slide as dω/dt; here it is α = ω̇, the same quantity.)

A 3 kg box spins at 3 rad/s about its z axis while its centre drifts at 0.5 m/s; a
constant 6 N force pushes it along z and a torque of 0.26 N·m spins it up at 2 rad/s².
rigidlab's b:point_velocity gives the velocity of its corner directly. For the
acceleration we let a world move the box (RK4, two steps of h = 1e-4 s) and difference
the corner's velocity, (v(t + h) − v(t − h))/2h; that estimate is good to about h² times
the corner's fourth derivative (≈ 1e-7 m/s²), so we check it to 1e-5.]],
      formula = "x = x_cm + r,   v = v_cm + ω⃗ × r\n" ..
                "a = a_cm + α⃗ × r + ω⃗ × (ω⃗ × r)",
      run = function(ctx)
        local b = spinning_box()
        local corner = b:to_world(point_local)
        local r = corner - b.position
        ctx:show("x_cm (m)", b.position)
        ctx:show("corner x (m)", corner)
        ctx:show("r = x − x_cm (m)", r)
        local formula_velocity = b.velocity + b.angular_velocity:cross(r)
        ctx:show("v_cm + ω⃗ × r (m/s)", formula_velocity)
        ctx:show("b:point_velocity(x) (m/s)", b:point_velocity(corner))
        -- ω⃗ × r = (0, 0, 3) × (0.2, 0.3, 0.1) = (−0.9, 0.6, 0)
        ctx:expect("v = (0.5, 0, 0) + (−0.9, 0.6, 0)", b:point_velocity(corner),
                   vec3(-0.4, 0.6, 0), 1e-12)

        local h = 1e-4
        local w = world{gravity = vec3(0, 0, 0), integrator = "rk4"}
        w:add(b)
        w:add_force(function()
          b:apply_force(push)
          b:apply_torque(twist)
        end)
        local velocities, omega = {}, nil
        for i = 1, 3 do
          velocities[i] = b:point_velocity(b:to_world(point_local))
          if i == 2 then r, omega = b:to_world(point_local) - b.position, b.angular_velocity end
          if i < 3 then w:step(h) end
        end
        local measured = (velocities[3] - velocities[1]) / (2 * h)
        local a_cm = push / body_mass
        local izz = body_mass * (box_size.x ^ 2 + box_size.y ^ 2) / 12
        local alpha = twist / izz
        local formula = a_cm + alpha:cross(r) + omega:cross(omega:cross(r))
        ctx:show("a_cm = F/m (m/s²)", a_cm)
        ctx:show("α⃗ = τ/I_zz (rad/s²)", alpha)
        ctx:show("ω⃗ at the middle time (rad/s)", omega)
        ctx:show("α⃗ × r (m/s²)", alpha:cross(r))
        ctx:show("ω⃗ × (ω⃗ × r) (m/s²)", omega:cross(omega:cross(r)))
        ctx:show("a by the formula (m/s²)", formula)
        ctx:show("a measured in the world (m/s²)", measured)
        ctx:expect("a = a_cm + α⃗ × r + ω⃗ × (ω⃗ × r) (central difference)", measured,
                   formula, {abs = 1e-5})
      end,
    },
  },
}
