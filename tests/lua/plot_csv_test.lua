-- plot.lines draws what it is given (dimensions, labels, ranges, SVG) and csv.write writes
-- what reads back exactly.
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
    "column 'z' must be a list of numbers, got nil", "missing column")
  T.fails(function() csv.write("/nonexistent-dir/a.csv", {x = {1}}, {"x"}) end,
    "bad argument #1 to 'csv.write' (cannot open '/nonexistent-dir/a.csv' for writing", "path")
end)

os.remove(tmp)
T.finish()
