-- w:render: a frame of the asked size, pure (the world is unchanged, the same world gives the
-- same frame), overlays where their vectors point, ASCII without a byte above 127, colour only
-- when asked, and the agreed errors.
local T = dofile("testing.lua")

local function lines_of(text)
  local lines = {}
  for line in (text .. "\n"):gmatch("([^\n]*)\n") do lines[#lines + 1] = line end
  return lines
end

local function spinning_box()
  local w = world{gravity = vec3(0, 0, 0)}
  local b = w:add(body.box{mass = 2, size = vec3(0.5, 0.15, 1), angular_velocity = vec3(1, 0.3, 2)})
  return w, b
end

T.case("a frame has the asked size and changes nothing", function()
  local w = spinning_box()
  local frame = w:render{width = 50, height = 16, legend = false, ascii = true}
  local lines = lines_of(frame)
  T.equal(#lines, 16, "rows")
  for i, line in ipairs(lines) do T.equal(#line, 50, "columns of row " .. i) end
  T.equal(w.time, 0, "the world did not step")
  T.equal(w:render{width = 50, height = 16, legend = false, ascii = true}, frame, "pure")
  local lit = 0
  for _ in frame:gmatch("[^ \n]") do lit = lit + 1 end
  assert(lit > 30, "the box is drawn: " .. frame)
end)

T.case("ascii frames have no byte above 127; braille frames use U+2800..U+28FF", function()
  local w = spinning_box()
  w:add_plane{offset = -1}
  w:add(body.sphere{mass = 1, radius = 0.3, position = vec3(1, 0, 0)})
  local show = {"frames", "omega", "L", "ellipsoid", "contacts"}
  local ascii = w:render{ascii = true, show = show}
  assert(not ascii:find("[\128-\255]"), "ASCII only")
  local braille = w:render{ascii = false, show = show}
  assert(braille:find("\226\160[\128-\191]") or braille:find("\226\161[\128-\191]"), "braille dots")
  assert(not braille:find("\27", 1, true) and not ascii:find("\27", 1, true), "no colour unasked")
  assert(w:render{color = true}:find("\27[34m", 1, true), "colour when asked")
end)

-- The column and row of the first occurrence of `text` in the frame's rows.
local function find_cell(lines, text)
  for row, line in ipairs(lines) do
    local at = line:find(text, 1, true)
    if at then return at, row end
  end
end

T.case("overlays point where their vectors do", function()
  -- A sphere spinning about +x, seen from +z: x to the right, y up. L = I ω is along +x too.
  local w = world{gravity = vec3(0, 0, 0)}
  w:add(body.sphere{mass = 1, radius = 0.5, angular_velocity = vec3(3, 0, 0)})
  local camera = {eye = vec3(0, 0, 6), target = vec3(0, 0, 0)}
  local lines = lines_of(w:render{width = 61, height = 31, ascii = true, show = "omega",
                                  camera = camera, legend = false})
  local column, row = find_cell(lines, "w")
  assert(column and column > 31 + 5, "the label of omega is right of the centre: " .. tostring(column))
  assert(math.abs(row - 16) <= 1, "on the centre row: " .. tostring(row))
  -- Spinning about +y instead: the arrow points up.
  w:bodies()[1].angular_velocity = vec3(0, 3, 0)
  lines = lines_of(w:render{width = 61, height = 31, ascii = true, show = {"L"}, camera = camera,
                            legend = false})
  column, row = find_cell(lines, "L")
  assert(row and row < 16 - 3, "the label of L is above the centre: " .. tostring(row))
  assert(math.abs(column - 31) <= 1, "on the centre column: " .. tostring(column))
end)

T.case("the legend names bodies and overlays with their magnitudes", function()
  local w = spinning_box()
  local frame = w:render{show = {"omega", "L"}, ascii = true}
  assert(frame:find("1 box 0.5x0.15x1", 1, true), "the body")
  local omega = w:bodies()[1].angular_velocity:norm()
  assert(frame:find(string.format("angular velocity (%.4g rad/s)", omega), 1, true), frame)
  assert(frame:find("angular momentum (", 1, true), "L")
end)

T.case("trails come from the newest recorder", function()
  local w = world{gravity = vec3(0, -9.81, 0)}
  w:add(body.sphere{mass = 1, radius = 0.1, velocity = vec3(2, 4, 0)})
  T.fails(function() w:render{show = "trail"} end,
    "bad argument #1 to 'world:render' (field 'show': 'trail' needs a recorder", "no recorder")
  w:record{}
  w:step(1 / 60, 50)
  local frame = w:render{show = "trail", ascii = true}
  assert(frame:find(":", 1, true) and frame:find("trail", 1, true), frame)
end)

T.case("errors", function()
  local w = spinning_box()
  T.fails(function() w:render(5) end, "bad argument #1 to 'world:render' (table expected, got number)")
  T.fails(function() w:render{widht = 5} end,
    "bad argument #1 to 'world:render' (unknown field 'widht'", "misspelt")
  T.fails(function() w:render{width = 5} end,
    "bad argument #1 to 'world:render' (field 'width' must be an integer from 10 to 1000, got 5)")
  T.fails(function() w:render{show = {"omegas"}} end,
    "bad argument #1 to 'world:render' (field 'show' must be one of 'frames', 'omega', 'L'",
    "overlay")
  T.fails(function() w:render{camera = {eye = vec3(1, 2, 3), target = vec3(1, 2, 3)}} end,
    "bad argument #1 to 'world:render' (field 'camera': eye and target must differ)", "camera")
  T.fails(function() w:render{camera = {eye = vec3(0, 5, 0), target = vec3(0, 0, 0)}} end,
    "up must not be parallel to the line from eye to target", "up")
  T.fails(function() w:render{camera = {fov = 200}} end,
    "bad argument #1 to 'world:render' (field 'camera.fov' must be from 1 to 170 (degrees), got 200)")
  T.fails(function() w:render{camera = {eye = 1}} end,
    "bad argument #1 to 'world:render' (field 'camera.eye'", "eye type")
  T.fails(function() w:render{camera = {pos = vec3(1, 1, 1)}} end,
    "(field 'camera': unknown field 'pos'", "camera field")
  T.fails(function() w:render({}, 1) end, "bad argument #2 to 'world:render' (no more than")
  T.fails(function() world.render(5) end, "world expected, got number")
end)

T.case("art:render draws links from their joints, with joint markers", function()
  local art = articulation{gravity = vec3(0, 0, 0)}
  art:add_link{joint = "revolute", axis = vec3(0, 0, 1), mass = 1, com = vec3(1, 0, 0)}
  local lines = lines_of(art:render{width = 41, height = 21, ascii = true, show = "joints",
    legend = false, camera = {eye = vec3(0.5, 0, 6), target = vec3(0.5, 0, 0)}})
  local joint, row = find_cell(lines, "o")
  local com = lines[row] and lines[row]:find("+", 1, true)
  assert(joint and com and joint < com, "the joint left of the COM on one row: " .. table.concat(lines, "\n"))
  assert(lines[row]:sub(joint + 1, com - 1):find("^%-+$"), "a horizontal link between them")
  T.fails(function() art:render{show = "L"} end, "'L' is not drawn for articulations")
  T.fails(function() art:render{width = 3} end, "field 'width' must be an integer from 10 to 1000")
end)

T.case("w:render's 'joints' overlay draws each joint where it attaches", function()
  local w = world{gravity = vec3(0, 0, 0)}
  local b = body.sphere{mass = 1, radius = 0.1, position = vec3(1, 0, 0)}
  w:add(b)
  w:add_joint{type = "hinge", a = b, anchor = vec3(0, 0, 0), axis = vec3(0, 0, 1)}
  local view = {width = 41, height = 21, ascii = true, legend = false,
                camera = {eye = vec3(0.5, 0, 6), target = vec3(0.5, 0, 0)}}
  T.equal(find_cell(lines_of(w:render(view)), "o"), nil, "no marker without the overlay")
  view.show = "joints"
  local lines = lines_of(w:render(view))
  local anchor, row = find_cell(lines, "o")
  -- the camera looks at x = 0.5 from 6 m: the anchor (x = 0) is left of the centre column
  assert(anchor and anchor < 21, "a marker left of the centre: " .. table.concat(lines, "\n"))
  assert(lines[row]:sub(anchor + 1, anchor + 5):find("^%-+$"), "a line from it towards the COM")
  -- a rod between two bodies: a marker at each end, on the bodies' row
  local v = world{gravity = vec3(0, 0, 0)}
  local p, q = body.sphere{mass = 1, radius = 0.05, position = vec3(-1, 0, 0)},
               body.sphere{mass = 1, radius = 0.05, position = vec3(2, 0, 0)}
  v:add(p) v:add(q)
  v:add_joint{type = "distance", a = p, b = q}
  local rod = lines_of(v:render(view))
  local first, at = find_cell(rod, "o")
  local second = first and rod[at]:find("o", first + 1, true)
  assert(first and second and second - first > 10, "two ends far apart: " .. table.concat(rod, "\n"))
end)

T.case("w:view checks its options, and needs a terminal", function()
  local w = spinning_box()
  T.fails(function() w:view{dt = 0} end,
    "bad argument #1 to 'world:view' (field 'dt' must be from 1e-6 to 1 (s), got 0)")
  T.fails(function() w:view{speed = 100} end, "field 'speed' must be from 1/64 to 64")
  T.fails(function() w:view{histroy = 5} end, "unknown field 'histroy'")
  T.fails(function() w:view{show = "omegas"} end, "field 'show' must be one of")
  T.fails(function() w:view{} end, "'world:view': a live view needs a terminal")
  T.equal(w.time, 0, "nothing ran")
end)

T.case("export_html runs the world on and writes one page", function()
  local w = spinning_box()
  local path = os.tmpname()
  T.equal(w:export_html(path, {seconds = 0.5, fps = 10, show = {"omega", "trail"}}), 6, "frames")
  T.near(w.time, 0.5, 1e-12, "the world ran on")
  local page = io.open(path):read("a")
  os.remove(path)
  assert(page:find("^<!DOCTYPE html>") and page:find("</html>\n$"), "a whole page")
  local _, frames = page:gsub('{"t":', "")
  T.equal(frames, 6, "one frame of data per frame")
  T.fails(function() w:export_html(path, {seconds = -1}) end,
    "bad argument #2 to 'world:export_html' (field 'seconds' must be in [0, 3600] (s), got -1)")
  T.fails(function() w:export_html(path, {fps = 1e9}) end, "field 'fps' must be from 1 to 240")
  T.fails(function() w:export_html(path, {seconds = 3600, fps = 240}) end,
    "seconds x fps must be at most 20000 frames")
  T.fails(function() w:export_html(path, {show = "spin"}) end, "field 'show' must be one of")
  T.fails(function() w:export_html(path .. "\0x") end, "must not contain a NUL byte")
  T.fails(function() w:export_html("/dev/full", {seconds = 0}) end,
    "bad argument #1 to 'world:export_html' (cannot write '/dev/full': No space left on device)")
  T.fails(function() w:export_html(path, {dt = 0}) end, "field 'dt'")
end)

T.case("ctx:motion steps as w:step does, and checks everything first", function()
  local ctx = lesson_context()
  local w, b = spinning_box()
  local twin, twin_body = spinning_box()
  T.fails(function() ctx:motion(w, {frames = 0}) end,
    "bad argument #2 to 'ctx:motion' (field 'frames' must be an integer from 1 to 12, got 0)")
  T.fails(function() ctx:motion(w, {seconds = -1}) end, "field 'seconds' must be from 0.001 to 600")
  T.fails(function() ctx:motion(w, {frame = 3}) end, "unknown field 'frame'")
  T.fails(function() ctx:motion(w, {show = "omegas"}) end, "field 'show' must be one of")
  T.fails(function() ctx:motion(42) end, "bad argument #1 to 'ctx:motion' (world or articulation expected")
  T.fails(function() ctx.motion(42, w) end, "lesson context expected")
  local art = articulation{gravity = vec3(0, 0, 0)}
  art:add_link{joint = "revolute", axis = vec3(0, 0, 1), mass = 1, com = vec3(1, 0, 0)}
  T.fails(function() ctx:motion(art, {show = "L"}) end, "'L' is not drawn for articulations")
  T.equal(w.time, 0, "a refused call stepped nothing")
  -- 3 intervals of round(0.5 / (1/60)) = 30 steps: the state w:step(1/60, 90) reaches.
  ctx:motion(w, {seconds = 1.5, frames = 4, ascii = true, show = {"omega", "trail"}})
  twin:step(1 / 60, 90)
  T.equal(w.time, twin.time, "time")
  T.equal(b.orientation, twin_body.orientation, "orientation, bit for bit")
  T.equal(b.angular_velocity, twin_body.angular_velocity, "ω, bit for bit")
  ctx:motion(w, {frames = 1})  -- one frame: the state now, no step
  T.equal(w.time, twin.time, "one frame steps nothing")
end)

T.finish()
