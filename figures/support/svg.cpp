#include "support/svg.hpp"

#include "exactpixels/base/atomic_file.hpp"

#include "exactpixels/base/error.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <system_error>

namespace exactpixels {

namespace {
std::string escape(const std::string& text) {
    std::string out;
    for (const char ch : text) {
        switch (ch) {
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '&':
            out += "&amp;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += ch;
        }
    }
    return out;
}
} // namespace

SvgDiagram::SvgDiagram(int width, int height, double scale, double margin)
    : width_(width), height_(height), scale_(scale), margin_(margin) {
    if (width < 0 || height < 0 || !(scale > 0) || !(margin >= 0)) {
        throw Error(fmt::format("SvgDiagram: bad size {}x{}, scale {}, margin {}", width,
                                height, scale, margin));
    }
}

std::string SvgDiagram::attributes(const SvgStyle& style) {
    std::string a = fmt::format(R"(stroke="{}" fill="{}" stroke-width="{:g}")",
                                escape(style.stroke), escape(style.fill), style.width);
    if (style.opacity != 1.0) {
        a += fmt::format(R"( opacity="{:g}")", style.opacity);
    }
    if (style.dashed) {
        a += fmt::format(R"( stroke-dasharray="{:g} {:g}")", 4 * style.width,
                         3 * style.width);
    }
    return a;
}

void SvgDiagram::fill_pixel(int x, int y, const std::string& colour, double opacity) {
    body_.push_back(fmt::format(R"(<rect x="{:g}" y="{:g}" width="{:g}" height="{:g}" )"
                                R"(fill="{}" opacity="{:g}"/>)",
                                sx(x), sy(y), scale_, scale_, escape(colour), opacity));
}

void SvgDiagram::grid(const std::string& colour) {
    std::string path;
    for (int x = 0; x <= width_; ++x) {
        path += fmt::format("M{:g} {:g}V{:g}", sx(x), sy(0), sy(height_));
    }
    for (int y = 0; y <= height_; ++y) {
        path += fmt::format("M{:g} {:g}H{:g}", sx(0), sy(y), sx(width_));
    }
    body_.push_back(
        fmt::format(R"(<path d="{}" stroke="{}" stroke-width="0.75" fill="none"/>)", path,
                    escape(colour)));
}

void SvgDiagram::grid_labels(double size) {
    for (int x = 0; x < width_; ++x) {
        text({x + 0.5, -0.25}, std::to_string(x), size, SvgAnchor::middle, "#606060");
    }
    for (int y = 0; y < height_; ++y) {
        const double baseline = y + 0.5 + 0.35 * size / scale_;
        text({-0.2, baseline}, std::to_string(y), size, SvgAnchor::end, "#606060");
    }
}

void SvgDiagram::line(Point2 a, Point2 b, const SvgStyle& style) {
    body_.push_back(fmt::format(R"(<line x1="{:g}" y1="{:g}" x2="{:g}" y2="{:g}" {}/>)",
                                sx(a.x), sy(a.y), sx(b.x), sy(b.y), attributes(style)));
}

void SvgDiagram::polygon(const std::vector<Point2>& points, const SvgStyle& style) {
    std::string list;
    for (const Point2& p : points) {
        list += fmt::format("{}{:g},{:g}", list.empty() ? "" : " ", sx(p.x), sy(p.y));
    }
    body_.push_back(fmt::format(R"(<polygon points="{}" {}/>)", list, attributes(style)));
}

void SvgDiagram::circle(Point2 centre, double radius, const SvgStyle& style) {
    body_.push_back(fmt::format(R"(<circle cx="{:g}" cy="{:g}" r="{:g}" {}/>)",
                                sx(centre.x), sy(centre.y), radius, attributes(style)));
}

void SvgDiagram::arrow(Point2 from, Point2 to, const SvgStyle& style) {
    const double dx = sx(to.x) - sx(from.x), dy = sy(to.y) - sy(from.y);
    const double length = std::hypot(dx, dy);
    if (length == 0) {
        return; // no direction: nothing to point with
    }
    // The head: a triangle of length `head` along the shaft, half as wide each side.
    const double head = 6.0 + 2.0 * style.width;
    const double ux = dx / length, uy = dy / length;
    const double bx = sx(to.x) - head * ux, by = sy(to.y) - head * uy;
    line(from, {to.x - head * ux / scale_, to.y - head * uy / scale_}, style);
    body_.push_back(fmt::format(
        R"(<polygon points="{:g},{:g} {:g},{:g} {:g},{:g}" fill="{}" stroke="none"{}/>)",
        sx(to.x), sy(to.y), bx - 0.5 * head * uy, by + 0.5 * head * ux,
        bx + 0.5 * head * uy, by - 0.5 * head * ux, escape(style.stroke),
        style.opacity != 1.0 ? fmt::format(R"( opacity="{:g}")", style.opacity) : ""));
}

void SvgDiagram::text(Point2 at, const std::string& text, double size, SvgAnchor anchor,
                      const std::string& colour) {
    const char* anchors[] = {"start", "middle", "end"};
    body_.push_back(fmt::format(
        R"(<text x="{:g}" y="{:g}" font-family="sans-serif" font-size="{:g}" )"
        R"(text-anchor="{}" fill="{}">{}</text>)",
        sx(at.x), sy(at.y), size, anchors[static_cast<int>(anchor)], escape(colour),
        escape(text)));
}

std::string SvgDiagram::str() const {
    const double w = 2 * margin_ + scale_ * width_, h = 2 * margin_ + scale_ * height_;
    std::string out = fmt::format(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:g}\" height=\"{:g}\" "
        "viewBox=\"0 0 {:g} {:g}\">\n<rect width=\"100%\" height=\"100%\" "
        "fill=\"white\"/>\n",
        w, h, w, h);
    for (const std::string& element : body_) {
        out += element;
        out += '\n';
    }
    out += "</svg>\n";
    return out;
}

void SvgDiagram::write(const std::filesystem::path& path) const {
    write_file_atomically(path, "SVG", str());
}

} // namespace exactpixels
