// svg.hpp: diagrams on a pixel grid, written as SVG text (for the book's figures).
//
// Usage:
//   SvgDiagram d(8, 6, 40.0);                 // an 8 x 6 pixel grid, 40 SVG units per px
//   d.fill_pixel(2, 3, "#cde");               // shade pixel (2, 3)
//   d.grid();                                 // pixel boundaries, light grey
//   d.polygon({{0.5, 0.5}, {7.2, 1.0}, {3.0, 5.5}}, {.stroke = "black"});
//   d.circle(pixel_centre(2, 3), 4.0, {.fill = "black"});   // radius in SVG units
//   d.arrow({3, 3}, {5, 2}, {.stroke = "#c00", .width = 2});
//   d.text({3, 3}, "dc/dx", 14);
//   d.write(folder / "ch01_grid.svg");          // throws Error naming the path
//
// Every position is in pixels with the book's conventions (origin top-left, y down,
// pixel (x, y) covers [x, x+1) x [y, y+1)), so a point drawn at pixel_centre(x, y)
// lands in the middle of that grid cell. The diagram maps pixel p to SVG point
// margin + scale * p; sizes of markers, strokes and text are in SVG units, so they do
// not grow with the scale. Colours are any SVG colour string ("black", "#c00").
#pragma once

#include "exactpixels/base/types.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace exactpixels {

/// How a shape is drawn. Plain aggregate: set only what differs from the defaults.
struct SvgStyle {
    std::string stroke = "black"; ///< outline colour ("none" for no outline)
    std::string fill = "none";    ///< fill colour ("none" for no fill)
    double width = 1.0;           ///< stroke width in SVG units
    double opacity = 1.0;         ///< 0 transparent .. 1 opaque, for fill and stroke
    bool dashed = false;          ///< a dashed outline
};

/// Text placement relative to its anchor point.
enum class SvgAnchor { start, middle, end };

/// An SVG drawing over a width x height pixel grid; shapes are kept in drawing order
/// (later shapes on top) and written out by str() or write().
class SvgDiagram {
  public:
    /// A diagram of width x height pixels, `scale` SVG units per pixel (> 0), with a
    /// blank border of `margin` SVG units. Throws Error for a negative size or a scale
    /// that is not positive.
    SvgDiagram(int width, int height, double scale, double margin = 24.0);

    /// Fills the square of pixel (x, y) with `colour`.
    void fill_pixel(int x, int y, const std::string& colour, double opacity = 1.0);
    /// The pixel boundaries, as thin lines, and the frame around the grid.
    void grid(const std::string& colour = "#b0b0b0");
    /// Numbers the columns along the top and the rows down the left side.
    void grid_labels(double size = 11.0);
    /// A straight line from a to b.
    void line(Point2 a, Point2 b, const SvgStyle& style = {});
    /// A closed polygon through the points, in order.
    void polygon(const std::vector<Point2>& points, const SvgStyle& style = {});
    /// A circle at `centre` of `radius` SVG units (a marker: its size ignores scale).
    void circle(Point2 centre, double radius, const SvgStyle& style = {});
    /// A line from `from` to `to` with an arrow head at `to`, in the stroke colour.
    void arrow(Point2 from, Point2 to, const SvgStyle& style = {});
    /// Text of `size` SVG units with its baseline through `at`. '<', '>', '&' are
    /// escaped, so any text is safe.
    void text(Point2 at, const std::string& text, double size = 12.0,
              SvgAnchor anchor = SvgAnchor::start, const std::string& colour = "black");

    /// The whole document as SVG text.
    std::string str() const;
    /// Writes str() to `path` (all or nothing, like write_png). Throws Error naming the
    /// path on failure.
    void write(const std::filesystem::path& path) const;

  private:
    double sx(double x) const { return margin_ + scale_ * x; }
    double sy(double y) const { return margin_ + scale_ * y; }
    static std::string attributes(const SvgStyle& style);

    int width_;
    int height_;
    double scale_;
    double margin_;
    std::vector<std::string> body_;
};

} // namespace exactpixels
