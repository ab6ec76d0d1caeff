// Tests for present/svg_chart.cpp: the document is well-formed XML whatever the labels hold
// (checked by a small reader of the XML 1.0 grammar written here: UTF-8, the Char production,
// entity references, balanced tags), ticks and grid lines fall on round numbers.
#include "present/svg_chart.hpp"

#include <gtest/gtest.h>

#include <regex>
#include <vector>

namespace rigidlab::present {
namespace {

// Whether `doc` is well-formed as far as the parts an SVG writer can get wrong go: every
// character valid UTF-8 and an XML Char; '&' only in &lt; &gt; &amp; &quot; &apos;; '<' only
// opening tags, closing tags matching them, and self-closing tags; '>' only ending a tag.
// `why` says what failed.
bool well_formed(const std::string& doc, std::string& why) {
  std::vector<std::string> open;
  for (std::size_t i = 0; i < doc.size();) {
    const unsigned char c = doc[i];
    if (c >= 0x80) {  // a UTF-8 sequence: length from the first byte, continuations 10xxxxxx
      const int n = c >= 0xF0 ? 4 : c >= 0xE0 ? 3 : c >= 0xC0 ? 2 : 0;
      if (n == 0 || i + n > doc.size()) return why = "bad UTF-8 lead byte", false;
      unsigned code = c & (0x7F >> n);
      for (int k = 1; k < n; ++k) {
        if ((doc[i + k] & 0xC0) != 0x80) return why = "bad UTF-8 continuation", false;
        code = (code << 6) | (doc[i + k] & 0x3F);
      }
      const unsigned smallest[] = {0, 0, 0x80, 0x800, 0x10000};
      if (code < smallest[n] || (code >= 0xD800 && code <= 0xDFFF) || code == 0xFFFE ||
          code == 0xFFFF || code > 0x10FFFF)
        return why = "not an XML Char: " + std::to_string(code), false;
      i += n;
      continue;
    }
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r')
      return why = "control character " + std::to_string(c), false;
    if (c == '&') {
      bool ok = false;
      for (const char* e : {"&lt;", "&gt;", "&amp;", "&quot;", "&apos;"})
        ok = ok || doc.compare(i, std::string(e).size(), e) == 0;
      if (!ok) return why = "bare &", false;
    }
    if (c == '>') return why = "> outside a tag", false;
    if (c == '<') {
      const std::size_t end = doc.find('>', i);
      if (end == std::string::npos) return why = "unterminated tag", false;
      std::string tag = doc.substr(i + 1, end - i - 1);
      if (tag.find('<') != std::string::npos) return why = "< inside a tag", false;
      // Attribute values hold no '<' and come quoted; a '"' count must be even.
      if (std::count(tag.begin(), tag.end(), '"') % 2) return why = "odd quotes in " + tag, false;
      if (tag[0] == '/') {
        if (open.empty() || open.back() != tag.substr(1)) return why = "mismatched </" + tag, false;
        open.pop_back();
      } else if (tag.back() != '/') {
        open.push_back(tag.substr(0, tag.find(' ')));
      }
      i = end + 1;
      continue;
    }
    ++i;
  }
  if (!open.empty()) return why = "unclosed <" + open.back() + ">", false;
  return true;
}

Chart sample() {
  Chart chart;
  chart.series.push_back(Series{{0, 5, 10}, {0.2, 0.9, 0.4}, "first"});
  chart.series.push_back(Series{{0, 10}, {0.5, 0.1}, "second"});
  chart.title = "energy";
  chart.xlabel = "t (s)";
  chart.ylabel = "E (J)";
  return chart;
}

TEST(SvgChart, IsWellFormedWhateverTheLabelsHold) {
  Chart chart = sample();
  chart.title = "a < b & c > \"d\" 'e'";
  chart.xlabel = std::string("nul \0 bell \a esc \x1b", 17);
  chart.ylabel = "broken \xC3 utf-8 \xED\xA0\x80 \xEF\xBF\xBE";
  chart.series[0].label = "]]> <!-- --> <script>";
  chart.series[1].label = "\x7f\xC2\x85";
  std::string why;
  EXPECT_TRUE(well_formed(svg_chart(chart), why)) << why;
  // The reader above catches what it should.
  EXPECT_FALSE(well_formed("<svg>a \x01</svg>", why));
  EXPECT_FALSE(well_formed("<svg>a & b</svg>", why));
  EXPECT_FALSE(well_formed("<svg>\xC3</svg>", why));
  EXPECT_FALSE(well_formed("<svg><text></svg>", why));
}

TEST(SvgChart, TicksAndGridLinesAtRoundNumbers) {
  const std::string svg = svg_chart(sample());
  std::vector<std::string> labels;
  const std::regex text("<text x=\"[0-9.]+\" y=\"[0-9.]+\" text-anchor=\"(end|middle)\">([^<]*)</text>");
  for (std::sregex_iterator it(svg.begin(), svg.end(), text), end; it != end; ++it)
    labels.push_back((*it)[2]);
  // y from 0.1 to 0.9 with at most 7 ticks: steps of 0.2 from 0 to 1; x from 0 to 10 with at
  // most 9: steps of 2 (a step of 1 would need 11).
  for (const char* want : {"0.0", "0.2", "0.4", "0.6", "0.8", "1.0", "0", "2", "4", "6", "8", "10"})
    EXPECT_NE(std::find(labels.begin(), labels.end(), want), labels.end()) << want;
  const std::regex grid("stroke=\"#ddd\"");
  const auto lines = std::distance(std::sregex_iterator(svg.begin(), svg.end(), grid),
                                   std::sregex_iterator());
  EXPECT_EQ(lines, 6 + 6);
  EXPECT_EQ(svg.rfind("</svg>\n"), svg.size() - 7);
}

TEST(SvgChart, OnePolylinePerSeriesAndALegendEntry) {
  const std::string svg = svg_chart(sample());
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
  EXPECT_NE(svg.find("<polyline", svg.find("<polyline") + 1), std::string::npos);
  EXPECT_NE(svg.find(">first</text>"), std::string::npos);
  EXPECT_NE(svg.find(">second</text>"), std::string::npos);
  // The polyline of the first series starts at the left edge, at y = 0.2 of 0 .. 1.
  const std::regex first("<polyline [^>]*points=\"([0-9.]+),([0-9.]+) ");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(svg, m, first));
  EXPECT_NEAR(std::stod(m[1]), 80, 1e-9);             // the plot area's left edge
  EXPECT_NEAR(std::stod(m[2]), 50 + 0.8 * 310, 0.01);  // top 50, height 440 - 50 - 80
}

}  // namespace
}  // namespace rigidlab::present
