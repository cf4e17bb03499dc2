/// \file SvgPlot.cpp
/// Log-log line plots as SVG, for the benchmarks' error-against-run-time studies.

#include "app/bench/SvgPlot.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gale::app {

std::string logLogSvg(const std::string& title, const std::string& xLabel,
                      const std::string& yLabel, const std::vector<Series>& series) {
    double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
    for (const Series& s : series)
        for (const auto& p : s.xy)
            if (p[0] > 0 && p[1] > 0)
                xmin = std::min(xmin, p[0]), xmax = std::max(xmax, p[0]),
                ymin = std::min(ymin, p[1]), ymax = std::max(ymax, p[1]);
    const double lx0 = std::floor(std::log10(xmin)),
                 lx1 = std::max(lx0 + 1, std::ceil(std::log10(xmax)));
    const double ly0 = std::floor(std::log10(ymin)),
                 ly1 = std::max(ly0 + 1, std::ceil(std::log10(ymax)));
    const double W = 760, H = 500, ml = 80, mr = 210, mt = 44, mb = 60, pw = W - ml - mr,
                 ph = H - mt - mb;
    auto X = [&](double x) { return ml + (std::log10(x) - lx0) / (lx1 - lx0) * pw; };
    auto Y = [&](double y) { return mt + (1.0 - (std::log10(y) - ly0) / (ly1 - ly0)) * ph; };
    std::ostringstream o;
    o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' "
         "fill='white'/>\n";
    o << "<text x='" << ml + pw / 2 << "' y='24' text-anchor='middle' font-size='15'>" << title
      << "</text>\n";
    for (double d = lx0; d <= lx1 + 1e-9; d += 1) {
        o << "<line x1='" << X(std::pow(10, d)) << "' y1='" << mt << "' x2='" << X(std::pow(10, d))
          << "' y2='" << mt + ph << "' stroke='#ddd'/>\n<text x='" << X(std::pow(10, d)) << "' y='"
          << mt + ph + 18 << "' text-anchor='middle'>1e" << int(d) << "</text>\n";
    }
    for (double d = ly0; d <= ly1 + 1e-9; d += 1) {
        o << "<line x1='" << ml << "' y1='" << Y(std::pow(10, d)) << "' x2='" << ml + pw << "' y2='"
          << Y(std::pow(10, d)) << "' stroke='#ddd'/>\n<text x='" << ml - 6 << "' y='"
          << Y(std::pow(10, d)) + 4 << "' text-anchor='end'>1e" << int(d) << "</text>\n";
    }
    o << "<rect x='" << ml << "' y='" << mt << "' width='" << pw << "' height='" << ph
      << "' fill='none' stroke='black'/>\n";
    o << "<text x='" << ml + pw / 2 << "' y='" << H - 16 << "' text-anchor='middle'>" << xLabel
      << "</text>\n";
    o << "<text transform='translate(18," << mt + ph / 2 << ") rotate(-90)' text-anchor='middle'>"
      << yLabel << "</text>\n";
    for (size_t n = 0; n < series.size(); ++n) {
        const Series& s = series[n];
        o << "<polyline fill='none' stroke='" << s.colour << "' stroke-width='2'"
          << (s.dashed ? " stroke-dasharray='6,4'" : "") << " points='";
        for (const auto& p : s.xy) o << X(p[0]) << "," << Y(p[1]) << " ";
        o << "'/>\n";
        for (size_t k = 0; k < s.xy.size(); ++k) {
            o << "<circle cx='" << X(s.xy[k][0]) << "' cy='" << Y(s.xy[k][1]) << "' r='3.5' fill='"
              << s.colour << "'/>\n";
            if (k < s.labels.size())
                o << "<text x='" << X(s.xy[k][0]) + 5 << "' y='" << Y(s.xy[k][1]) - 5
                  << "' font-size='10' fill='" << s.colour << "'>" << s.labels[k] << "</text>\n";
        }
        const double ly = mt + 16 + 20 * n;
        o << "<line x1='" << ml + pw + 12 << "' y1='" << ly << "' x2='" << ml + pw + 40 << "' y2='"
          << ly << "' stroke='" << s.colour << "' stroke-width='2'"
          << (s.dashed ? " stroke-dasharray='6,4'" : "") << "/>\n<text x='" << ml + pw + 46
          << "' y='" << ly + 4 << "'>" << s.name << "</text>\n";
    }
    o << "</svg>\n";
    return o.str();
}

}  // namespace gale::app
