-- Moments of forces (004 "Law of the Lever", "Moment", "Net Force and Net Torque"): the
-- lever balances when F₁h₁ = F₂h₂, the moment r × F has magnitude h·F, and forces and their
-- moments about a reference point simply add.

local dt = 0.01   -- s, one step of the world in which the forces act

-- One step of a weightless world in which `forces` ({force =, point =} in world coordinates)
-- act on body b; returns the body after the step.
local function push_for_one_step(b, forces)
  local w = world{gravity = vec3(0, 0, 0)}
  w:add(b)
  for _, f in ipairs(forces) do b:apply_force(f.force, f.point) end
  w:step(dt)
  return b
end

-- Net force and net moment about `reference` of a list of {force =, point =}.
local function net(forces, reference)
  local force, moment = vec3(0, 0, 0), vec3(0, 0, 0)
  for _, f in ipairs(forces) do
    force = force + f.force
    moment = moment + (f.point - reference):cross(f.force)
  end
  return force, moment
end

return lesson{
  id = "lever-and-moment",
  title = "Levers, moments, and adding up forces",
  source = "004_8f5d2bfd6f0c2787.txt, \"Law of the Lever\", \"Moment\", " ..
           "\"Net Force and Net Torque\"",
  steps = {
    {
      title = "The law of the lever",
      text = [[
A seesaw balances when the turning efforts on both sides match, and a turning effort is
force times arm: F₁·h₁ = F₂·h₂, where each h is the distance from the pivot to where that
force acts (measured perpendicular to the force). A 30 N weight 0.5 m left of the pivot is
balanced by only 10 N placed 1.5 m to the right: three times the arm, a third of the force.
That is the whole trick of crowbars and bottle openers.

Written with cross products the two moments are r₁ × F₁ = +15 N·m and r₂ × F₂ = −15 N·m
about z: equal and opposite. We hang both weights on a plank of 2 kg and 4 × 0.1 × 0.1 m whose centre sits on
the pivot, in a world without gravity, and let the pivot push up with the 40 N it must carry. In a rigidlab world the plank
then neither falls nor turns. Make the right weight 12 N and it starts to tip.

A small slip on the slide: it says "a level is in equilibrium" where "a lever" is meant.
It prints F₁ and F₂ in bold, as vectors; read the law as one about their sizes and arms,
since what balances are two moments of opposite sense (+15 and −15 N·m here).]],
      formula = "F₁·h₁ = F₂·h₂   (magnitudes; h measured from the pivot)",
      run = function(ctx)
        local h1, h2, f1 = 0.5, 1.5, 30
        local f2 = f1 * h1 / h2
        ctx:show("F₂ = F₁·h₁/h₂ (N)", f2)
        ctx:expect("F₂ = 30 · 0.5 / 1.5", f2, 10)
        local left = {force = vec3(0, -f1, 0), point = vec3(-h1, 0, 0)}
        local right = {force = vec3(0, -f2, 0), point = vec3(h2, 0, 0)}
        local pivot = {force = vec3(0, f1 + f2, 0), point = vec3(0, 0, 0)}
        ctx:show("moment of F₁ about the pivot (N·m)", left.point:cross(left.force))
        ctx:show("moment of F₂ about the pivot (N·m)", right.point:cross(right.force))
        local _, moment = net({left, right}, vec3(0, 0, 0))
        ctx:expect("the moments cancel", moment, vec3(0, 0, 0), {abs = 1e-12})

        local plank = push_for_one_step(body.box{mass = 2, size = vec3(4, 0.1, 0.1)},
                                        {left, right, pivot})
        ctx:show("balanced plank: v after the step (m/s)", plank.velocity)
        ctx:show("balanced plank: ω after the step (rad/s)", plank.angular_velocity)
        ctx:expect("balanced: it does not turn", plank.angular_velocity, vec3(0, 0, 0),
                   {abs = 1e-12})
        ctx:expect("balanced: it does not move", plank.velocity, vec3(0, 0, 0), {abs = 1e-12})

        local heavier = {force = vec3(0, -12, 0), point = right.point}
        local lift = {force = vec3(0, f1 + 12, 0), point = vec3(0, 0, 0)}
        local tipping = push_for_one_step(body.box{mass = 2, size = vec3(4, 0.1, 0.1)},
                                          {left, heavier, lift})
        ctx:show("12 N on the right: angular momentum after the step (kg·m²/s)",
                 tipping:angular_momentum())
        ctx:expect("L = (15 − 18) N·m · Δt, clockwise", tipping:angular_momentum(),
                   vec3(0, 0, (f1 * h1 - 12 * h2) * dt), 1e-12)
      end,
    },
    {
      title = "Moment = arm × force",
      text = [[
In general the moment of a force about a reference point x is M = (r_F − x) × F, with r_F
where the force acts. Its direction is the axis the force tries to turn about,
perpendicular to both the force and the arm. Its size is the force times h, the distance
from the reference point to the force's line of action: the cross product keeps only the
part of the arm that sticks out sideways from the force.

Take F = (3, 4, 0) N (5 N strong) acting at (2, 1, 0) m, with the origin as reference. The
cross product gives M = (0, 0, 5) N·m. Independently, the line of action passes the origin
at a distance h = 1 m, and h·F = 1 · 5 = 5. Sliding the force along its own line changes
nothing: the moment depends on the line, not on the point chosen on it.]],
      formula = "M_F^(x) = (r_F − x) × F,   ‖M‖ = h·F",
      run = function(ctx)
        local force = vec3(3, 4, 0)
        local point = vec3(2, 1, 0)
        local moment = point:cross(force)
        ctx:show("M = r × F (N·m)", moment)
        local direction = force:normalized()
        local foot = direction * point:dot(direction)    -- closest point of the line to 0
        local h = (point - foot):norm()
        ctx:show("h, distance from the origin to the line of action (m)", h)
        ctx:show("h·F (N·m)", h * force:norm())
        ctx:expect("M = (0, 0, 2·4 − 1·3)", moment, vec3(0, 0, 5))
        ctx:expect("‖M‖ = h·F = 1 · 5", moment:norm(), 5, 1e-12)
        ctx:expect("M ⟂ F and M ⟂ r", {moment:dot(force), moment:dot(point)}, {0, 0})
        local slid = point + direction * 3
        ctx:show("same force applied 3 m further along its line, M (N·m)", slid:cross(force))
        ctx:expect("moment unchanged along the line of action", slid:cross(force),
                   vec3(0, 0, 5), 1e-12)
      end,
    },
    {
      title = "Net force and net moment",
      text = [[
Several forces on one body add up in two independent tallies: the net force is the plain
sum, and the net moment about a chosen point is the sum of the individual moments about
that same point. The net force does not care about the reference point; the net moment
does, and moving the reference from x to y adds (x − y) × F_net. Only when the forces
cancel (a "couple", like two hands turning a steering wheel) is the moment the same about
every point.

A uniform 1 m cube of 6 kg, centred at (1, 0, 0), is pushed by three forces for one short
step in a rigidlab world. The step changes its momentum by F_net·Δt and its angular
momentum about its centre by M^(centre)·Δt, exactly the two tallies. (A cube turns equally
easily about every axis, so nothing else enters the first step.)]],
      formula = "F = Σ Fᵢ,   M^(x) = Σ (rᵢ − x) × Fᵢ,   M^(y) = M^(x) + (x − y) × F",
      run = function(ctx)
        local centre = vec3(1, 0, 0)
        local forces = {
          {force = vec3(0, 10, 0), point = vec3(1.5, 0, 0)},
          {force = vec3(-4, 0, 0), point = vec3(1, 0.5, 0)},
          {force = vec3(0, 0, 6), point = vec3(1, 0, -0.5)},
        }
        local force, about_centre = net(forces, centre)
        local _, about_origin = net(forces, vec3(0, 0, 0))
        ctx:show("net force F (N)", force)
        ctx:show("net moment about the cube's centre (N·m)", about_centre)
        ctx:show("net moment about the origin (N·m)", about_origin)
        -- (0.5,0,0)×(0,10,0) + (0,0.5,0)×(−4,0,0) + (0,0,−0.5)×(0,0,6)
        ctx:expect("F = (−4, 10, 6)", force, vec3(-4, 10, 6))
        ctx:expect("M about the centre = (0, 0, 5) + (0, 0, 2) + 0", about_centre,
                   vec3(0, 0, 7))
        ctx:expect("M about the origin = M about the centre + (centre − 0) × F", about_origin,
                   about_centre + centre:cross(force))

        local cube = push_for_one_step(body.box{mass = 6, size = vec3(1, 1, 1),
                                                position = centre}, forces)
        ctx:show("momentum after the step (kg·m/s)", cube:linear_momentum())
        ctx:show("angular momentum about the centre after the step (kg·m²/s)",
                 cube:angular_momentum())
        ctx:expect("p = F·Δt", cube:linear_momentum(), vec3(-4, 10, 6) * dt, 1e-12)
        ctx:expect("L = M^(centre)·Δt", cube:angular_momentum(), vec3(0, 0, 7) * dt, 1e-12)

        local couple = {{force = vec3(0, 3, 0), point = vec3(1, 0, 0)},
                        {force = vec3(0, -3, 0), point = vec3(-1, 0, 0)}}
        local couple_force, couple_origin = net(couple, vec3(0, 0, 0))
        local _, couple_elsewhere = net(couple, vec3(5, -2, 7))
        ctx:show("a couple: net force (N)", couple_force)
        ctx:show("a couple: moment about the origin (N·m)", couple_origin)
        ctx:show("a couple: moment about (5, −2, 7) (N·m)", couple_elsewhere)
        ctx:expect("a couple has the same moment about every point", couple_elsewhere,
                   vec3(0, 0, 6))
      end,
    },
  },
}
