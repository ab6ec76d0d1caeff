-- plot.lines draws what it is given (dimensions, labels, round-number ticks, series told apart
-- without colour, well-formed SVG) and csv.write writes what reads back exactly (numbers and
-- vec3 columns, in the order asked or sorted), refusing names it cannot write.
local T = dofile("testing.lua")

local function captured(fn)
  local lines = {}
  local real_print = print
  print = function(s) lines[#lines + 1] = s end
  local ok, err = pcall(fn)
  print = real_print
  if not ok then error(err, 2) end
  return table.concat(lines, "\n")
end

local tmp = os.tmpname()

T.case("a chart has the requested size, ranges, labels and legend", function()
  local out = captured(function()
    plot.lines{{x = {0, 1, 2}, y = {-1, 3, 0}, label = "first"}, {y = {1, 2, 1}, label = "second"},
      title = "T", xlabel = "time", ylabel = "height", width = 30, height = 8}
  end)
  local rows = {}
  for line in out:gmatch("[^\n]+") do rows[#rows + 1] = line end
  -- title, ylabel, 8 plot rows, axis, x range, xlabel, legend
  T.equal(#rows, 14, "line count")
  assert(rows[3]:find("^%s*3 "), "top of the y range is the largest y (3): " .. rows[3])
  assert(rows[10]:find("^%s*%-1 "), "bottom is the smallest y (-1): " .. rows[10])
  assert(rows[12]:find("0") and rows[12]:find("3%s*$"), "x range 0 .. 3: " .. rows[12])
  assert(out:find("first", 1, true) and out:find("second", 1, true), "legend")
  assert(out:find("time", 1, true) and out:find("height", 1, true), "axis labels")
end)

T.case("extreme ranges draw a line, without overflow", function()
  for _, series in ipairs({
    {x = {-1.7e308, 1.7e308}, y = {-1.7e308, 1.7e308}},  -- x_max - x_min overflows
    {x = {1, 2}, y = {1.7e308, 1.7e308}},                -- a flat range padded past 1.8e308
    {x = {1, 2}, y = {5e-324, 5e-324}},                  -- a flat range of the smallest double
    {x = {0, 5e-324}, y = {0, 5e-324}},                  -- a range whose half rounds to 0
  }) do
    local out = captured(function() plot.lines{series, width = 10, height = 4} end)
    local dots = 0
    for _ in out:gmatch("[*\226]") do dots = dots + 1 end
    assert(dots > 0, "a line is drawn: " .. out)
  end
end)

T.case("svg output", function()
  captured(function()
    plot.lines{{x = {0, 1}, y = {0, 1}, label = "a<b"}, {x = {0, 1}, y = {1, 0}}, svg = tmp}
  end)
  local svg = io.open(tmp):read("a")
  local _, polylines = svg:gsub("<polyline", "")
  T.equal(polylines, 2, "one polyline per series")
  assert(svg:find("a&lt;b", 1, true), "labels are escaped")
  assert(svg:find("^<svg") and svg:find("</svg>\n$"), "a whole document")
end)

T.case("without colour (in a pipe) each series has its own glyph, in the chart and legend", function()
  local out = captured(function()
    plot.lines{{y = {1, 3, 2, 5, 4, 6}, label = "first"}, {y = {6, 4, 5, 2, 3, 1}, label = "second"}}
  end)
  assert(not out:find("\27", 1, true), "no colour in a pipe")
  local legend = out:match("[^\n]*$")
  assert(legend:find("*", 1, true) and legend:find("+", 1, true), "glyphs in the legend: " .. legend)
  local body = out:sub(1, #out - #legend)
  assert(body:find("*", 1, true) and body:find("+", 1, true), "glyphs on the lines: " .. body)
end)

T.case("svg: ticks at round numbers, labels made well-formed XML", function()
  captured(function()
    plot.lines{{x = {0, 10}, y = {0.13, 2.87}, label = "a\0b\27[31m\xff"}, title = "<&>\1",
      svg = tmp}
  end)
  local svg = io.open(tmp):read("a")
  for _, tick in ipairs({"0", "1", "2", "3", "4", "6", "8", "10"}) do
    assert(svg:find(">" .. tick .. "</text>", 1, true), "tick " .. tick)
  end
  assert(not svg:find("[%z\1-\8\11\12\14-\31]"), "no control characters")
  assert(svg:find("&lt;&amp;&gt;", 1, true), "markup escaped")
  assert(utf8.len(svg), "valid UTF-8")
end)

T.case("names with a NUL byte are refused, not cut", function()
  T.fails(function() plot.lines{{y = {1, 2}}, svg = tmp .. "\0.svg"} end,
    "bad argument #1 to 'plot.lines' (field 'svg' must not contain a NUL byte", "svg")
  T.fails(function() csv.write(tmp .. "\0junk", {x = {1}}) end,
    "bad argument #1 to 'csv.write' (path must not contain a NUL byte", "csv path")
  T.fails(function() csv.write(tmp, {["a\0b"] = {1}}) end,
    "bad argument #2 to 'csv.write' (column name 'a", "csv column")
end)

T.case("a full disk is an error in the usual form", function()
  T.fails(function() csv.write("/dev/full", {x = {1, 2}}) end,
    "bad argument #1 to 'csv.write' (cannot write '/dev/full': No space left on device)", "csv")
  T.fails(function() captured(function() plot.lines{{y = {1, 2}}, svg = "/dev/full"} end) end,
    "bad argument #1 to 'plot.lines' (field 'svg': cannot write '/dev/full': No space left on device)",
    "svg")
end)

T.case("csv: vec3 columns, default order sorted, every column written", function()
  csv.write(tmp, {t = {0, 0.5}, p = {vec3(1, 2, 3), vec3(-4, 5.5, 1e-9)}})
  local lines = {}
  for line in io.lines(tmp) do lines[#lines + 1] = line end
  T.equal(lines[1], "p.x,p.y,p.z,t", "sorted, vec3 split")
  T.equal(lines[2], "1,2,3,0", "row 1")
  T.equal(lines[3], "-4,5.5,1e-09,0.5", "row 2")
  csv.write(tmp, {t = {0}, p = {vec3(1, 2, 3)}}, {"t", "p"})
  T.equal(io.lines(tmp)(), "t,p.x,p.y,p.z", "order given")
  T.fails(function() csv.write(tmp, {t = {0}, p = {1}}, {"t"}) end,
    "bad argument #3 to 'csv.write' (column 'p' is not in order", "left out of order")
  T.fails(function() csv.write(tmp, {t = {0}}, {"t", "t"}) end,
    "bad argument #3 to 'csv.write' (order lists 't' twice)", "twice")
  T.fails(function() csv.write(tmp, {p = {vec3(1, 2, 3), 5}}) end,
    "column 'p' entry 2 must be a vec3 like entry 1, got number", "mixed")
  T.fails(function() csv.write(tmp, {[1] = {1}}) end,
    "bad argument #2 to 'csv.write' (column names must be strings", "number key")
  T.fails(function() csv.write(tmp, {}) end,
    "bad argument #2 to 'csv.write' (at least one column expected)", "empty")
end)

T.case("csv round trip", function()
  local xs, ys = {0, 0.1, 1 / 3}, {1e-300, -2.5, math.pi}
  csv.write(tmp, {x = xs, y = ys}, {"x", "y"})
  local lines = {}
  for line in io.lines(tmp) do lines[#lines + 1] = line end
  T.equal(lines[1], "x,y", "header")
  T.equal(#lines, 4, "rows")
  for i = 1, 3 do
    local a, b = lines[i + 1]:match("^([^,]+),([^,]+)$")
    T.equal(tonumber(a), xs[i], "x exact")
    T.equal(tonumber(b), ys[i], "y exact")
  end
end)

T.case("errors", function()
  T.fails(function() plot.lines{} end,
    "bad argument #1 to 'plot.lines' (at least one series {x = {...}, y = {...}} expected)", "none")
  T.fails(function() plot.lines{{x = {1, 2}, y = {1}}} end, "series 1: x has 2 values but y has 1",
    "lengths")
  T.fails(function() plot.lines{{y = {1, 0/0}}} end, "series 1: y[2] is nan", "NaN")
  T.fails(function() plot.lines{{y = {1}, colour = 1}} end,
    "bad argument #1 to 'plot.lines' (series 1: unknown field 'colour' (fields are x, y, label))",
    "series field")
  T.fails(function() plot.lines{{y = {1}}, titel = "x"} end,
    "bad argument #1 to 'plot.lines' (unknown field 'titel'", "chart field")
  T.fails(function() plot.lines{{y = {1}}, width = 2} end,
    "bad argument #1 to 'plot.lines' (field 'width' must be an integer from 10 to 400, got 2)",
    "width")
  T.fails(function() plot.lines{{y = {1}}, height = 1e300} end,
    "bad argument #1 to 'plot.lines' (field 'height' must be an integer from 4 to 200, got 1e+300)",
    "height")
  T.fails(function() plot.lines(5) end, "bad argument #1 to 'plot.lines' (table expected, got number)",
    "not a table")
  T.fails(function() csv.write(tmp, 5, {"x"}) end,
    "bad argument #2 to 'csv.write' (table expected, got number)", "columns not a table")
  T.fails(function() csv.write(tmp, {x = {1, 1/0}}, {"x"}) end,
    "bad argument #2 to 'csv.write' (column 'x' entry 2 must be finite, got inf)", "inf")
  T.fails(function() csv.write(tmp, {x = {1, 2}, y = {1}}, {"x", "y"}) end,
    "bad argument #2 to 'csv.write' (column 'y' has 1 entries but column 'x' has 2)", "ragged")
  T.fails(function() csv.write(tmp, {x = {1}}, {"x", "z"}) end,
    "column 'z' must be a list of numbers or vec3, got nil", "missing column")
  T.fails(function() csv.write("/nonexistent-dir/a.csv", {x = {1}}, {"x"}) end,
    "bad argument #1 to 'csv.write' (cannot open '/nonexistent-dir/a.csv' for writing", "path")
end)

os.remove(tmp)
T.finish()
