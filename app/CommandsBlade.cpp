/// \file CommandsBlade.cpp
/// `gale blade`: the length-preserving bend (render/Bend.h) as numbers and as a drawing.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>

#include "app/Cli.h"
#include "app/Commands.h"
#include "app/io/AtomicFile.h"
#include "app/io/Errors.h"
#include "app/scene/SceneParser.h"
#include "base/Numbers.h"
#include "render/Bend.h"

namespace gale::app {
namespace {

constexpr double SVG_WIDTH = 520, SVG_HEIGHT = 440;
constexpr double MARGIN_LEFT = 60, MARGIN_RIGHT = 30, MARGIN_TOP = 60, MARGIN_BOTTOM = 60;
/// At most this many shell indices are labelled, so many shells stay legible.
constexpr int MAX_LABELS = 10;

void validate(const BladeOptions& o) {
    if (o.shells < 1 || o.shells > MAX_SHELLS)
        throw InputError("--shells: must be in 1.." + std::to_string(MAX_SHELLS) + " (got " +
                         std::to_string(o.shells) + ")");
    if (!std::isfinite(o.intensity) || std::abs(o.intensity) > 4.0)
        throw InputError("--intensity: must be in [-4, 4] (got " + std::to_string(o.intensity) +
                         ")");
    if (!std::isfinite(o.stiffness) || o.stiffness <= 0.0 || o.stiffness > 100.0)
        throw InputError("--stiffness: must be in (0, 100] (got " + std::to_string(o.stiffness) +
                         ")");
    if (!std::isfinite(o.height_m) || o.height_m <= 0.0 || o.height_m > 100.0)
        throw InputError("--height-m: must be in (0, 100] (got " + std::to_string(o.height_m) +
                         ")");
}

/// `digits` significant digits, with round-off below 1e-12 m shown as 0.
std::string num(double v, int digits = 4) { return formatG(std::abs(v) < 1e-12 ? 0.0 : v, digits); }

std::string escapeXml(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '<')
            out += "&lt;";
        else if (c == '>')
            out += "&gt;";
        else if (c == '&')
            out += "&amp;";
        else
            out += c;
    }
    return out;
}

}  // namespace

std::string bladeSvg(const BladeOptions& o) {
    validate(o);
    const std::vector<render::ShellOffset> shells =
        render::bendBlade(o.shells, static_cast<float>(o.height_m), static_cast<float>(o.intensity),
                          static_cast<float>(o.stiffness));
    const double h = o.height_m;
    // Bounds in metres (w across, n up), holding the bent blade, the upright one and the ground.
    double wMin = -0.15 * h, wMax = 0.15 * h, nMin = 0.0, nMax = h;
    for (const render::ShellOffset& s : shells) {
        wMin = std::min(wMin, double(s.w_m));
        wMax = std::max(wMax, double(s.w_m));
        nMin = std::min(nMin, double(s.n_m));
        nMax = std::max(nMax, double(s.n_m));
    }
    const double pad = 0.08 * h;
    wMin -= pad, wMax += pad, nMin -= (nMin < 0 ? pad : 0.0), nMax += pad;
    const double plotW = SVG_WIDTH - MARGIN_LEFT - MARGIN_RIGHT;
    const double plotH = SVG_HEIGHT - MARGIN_TOP - MARGIN_BOTTOM;
    const double scale = std::min(plotW / (wMax - wMin), plotH / (nMax - nMin));  // px per metre
    const double x0 = MARGIN_LEFT + 0.5 * (plotW - scale * (wMax - wMin)) - scale * wMin;
    const double y0 = MARGIN_TOP + 0.5 * (plotH - scale * (nMax - nMin)) + scale * nMax;
    auto X = [&](double w) { return x0 + scale * w; };
    auto Y = [&](double n) { return y0 - scale * n; };

    const render::ShellOffset tip = shells.back();
    const double tiltDeg = degreesFromRadians(render::tipTilt_rad(o.intensity));
    const double segment = h / o.shells;

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << SVG_WIDTH << "\" height=\""
        << SVG_HEIGHT << "\" viewBox=\"0 0 " << SVG_WIDTH << " " << SVG_HEIGHT
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    svg << "  <title>"
        << escapeXml("gale blade: " + std::to_string(o.shells) +
                     " shells, I = " + num(o.intensity) + ", stiffness " + num(o.stiffness))
        << "</title>\n";
    svg << "  <rect width=\"100%\" height=\"100%\" fill=\"#f7f5ef\"/>\n";
    svg << "  <text x=\"" << MARGIN_LEFT << "\" y=\"24\" font-size=\"15\" font-weight=\"bold\">"
        << "Blade bend: " << o.shells << " shells, I = " << num(o.intensity) << ", stiffness "
        << num(o.stiffness) << ", height " << num(h) << " m</text>\n";
    svg << "  <text x=\"" << MARGIN_LEFT << "\" y=\"42\" fill=\"#555\">"
        << "theta_j = theta_tip (j/N)^stiffness, theta_tip = (pi/2) I saturating short of the "
           "ground; every segment keeps S = "
        << num(segment) << " m</text>\n";
    // Ground line and label.
    svg << "  <line x1=\"" << MARGIN_LEFT - 20 << "\" y1=\"" << Y(0) << "\" x2=\""
        << SVG_WIDTH - MARGIN_RIGHT + 10 << "\" y2=\"" << Y(0)
        << "\" stroke=\"#7a5a2f\" stroke-width=\"3\"/>\n";
    svg << "  <text x=\"" << SVG_WIDTH - MARGIN_RIGHT << "\" y=\"" << Y(0) + 16
        << "\" text-anchor=\"end\" fill=\"#7a5a2f\">ground (shell 0)</text>\n";
    // The upright blade (I = 0) for reference.
    svg << "  <line x1=\"" << X(0) << "\" y1=\"" << Y(0) << "\" x2=\"" << X(0) << "\" y2=\"" << Y(h)
        << "\" stroke=\"#999\" stroke-width=\"1.5\" stroke-dasharray=\"5,4\"/>\n";
    svg << "  <text x=\"" << X(0) - 6 << "\" y=\"" << Y(h) - 6
        << "\" text-anchor=\"end\" fill=\"#888\">I = 0</text>\n";
    // Axes labels.
    svg << "  <text x=\"" << SVG_WIDTH / 2 << "\" y=\"" << SVG_HEIGHT - 14
        << "\" text-anchor=\"middle\" fill=\"#333\">w (m): along the wind</text>\n";
    svg << "  <text transform=\"translate(18," << SVG_HEIGHT / 2
        << ") rotate(-90)\" text-anchor=\"middle\" fill=\"#333\">n (m): along the normal</text>\n";
    // The bent blade: one segment per shell.
    svg << "  <polyline fill=\"none\" stroke=\"#3d8b2a\" stroke-width=\"4\" "
           "stroke-linejoin=\"round\" stroke-linecap=\"round\" points=\"";
    for (const render::ShellOffset& s : shells)
        svg << num(X(s.w_m), 7) << "," << num(Y(s.n_m), 7) << " ";
    svg << "\"/>\n";
    const int labelEvery = std::max(1, (o.shells + MAX_LABELS - 1) / MAX_LABELS);
    for (int i = 0; i <= o.shells; ++i) {
        const double x = X(shells[i].w_m), y = Y(shells[i].n_m);
        svg << "  <circle cx=\"" << num(x, 7) << "\" cy=\"" << num(y, 7)
            << "\" r=\"3\" fill=\"#1f4f14\"/>\n";
        if (i % labelEvery == 0 || i == o.shells)
            svg << "  <text x=\"" << num(x + 7, 7) << "\" y=\"" << num(y + 4, 7)
                << "\" font-size=\"10\" fill=\"#1f4f14\">" << i << "</text>\n";
    }
    svg << "  <text x=\"" << MARGIN_LEFT << "\" y=\"" << SVG_HEIGHT - 34 << "\" fill=\"#1f4f14\">"
        << "tip: w = " << num(tip.w_m) << " m, n = " << num(tip.n_m) << " m, tilt " << num(tiltDeg)
        << " deg</text>\n";
    svg << "</svg>\n";
    return svg.str();
}

int runBlade(const BladeOptions& o) {
    validate(o);
    const std::vector<render::ShellOffset> shells =
        render::bendBlade(o.shells, static_cast<float>(o.height_m), static_cast<float>(o.intensity),
                          static_cast<float>(o.stiffness));
    // The file first: if it cannot be written, nothing is printed and the exit code says so.
    if (!o.svgPath.empty()) {
        try {
            writeTextAtomic(o.svgPath, bladeSvg(o));
        } catch (const std::runtime_error& e) {
            throw InputError(std::string("--svg: ") + e.what());
        }
    }
    std::printf("i,n_m,w_m\n");
    for (size_t i = 0; i < shells.size(); ++i)
        std::printf("%zu,%.9g,%.9g\n", i, static_cast<double>(shells[i].n_m),
                    static_cast<double>(shells[i].w_m));
    if (!o.svgPath.empty()) std::fprintf(stderr, "gale: wrote %s\n", o.svgPath.c_str());
    return EXIT_OK;
}

void addBladeVerb(CLI::App& app, VerbTable& verbs) {
    auto options = std::make_shared<BladeOptions>();
    CLI::App* verb = app.add_subcommand(
        "blade",
        "Print the length-preserving bend of one blade as CSV (i,n_m,w_m); --svg draws it");
    verb->add_option("--shells", options->shells, "Shells above the ground, N")
        ->required()
        ->check(CLI::Range(1, MAX_SHELLS));
    verb->add_option("--intensity", options->intensity,
                     "Wind intensity I (1 tilts the tip 76 degrees; the tilt saturates short of "
                     "the ground; negative bends the other way)")
        ->required()
        ->check(CLI::Range(-4.0, 4.0));
    verb->add_option("--stiffness", options->stiffness,
                     "Stiffness gamma in theta_j = (pi/2) I (j/N)^gamma (1 is the paper's)")
        ->required()
        ->check(CLI::Range(1e-6, 100.0));
    verb->add_option("--height-m", options->height_m, "Blade height in metres")
        ->capture_default_str()
        ->check(CLI::Range(1e-6, 100.0));
    verb->add_option("--svg", options->svgPath, "Also write an SVG drawing of the blade here");
    verb->footer(EXIT_CODES_FOOTER);
    verbs.add(verb, [options] { return runBlade(*options); });
}

}  // namespace gale::app
