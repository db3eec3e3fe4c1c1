#pragma once
// One colour and one marker per line, as far apart as ten lines allow (the plots of the results
// folders: bench/svg_plot.cpp, bench/trajectory_plot.cpp).

#include <cstddef>
#include <iterator>

namespace eco::bench {

struct PlotStyle {
  const char* colour;
  const char* marker;  // an SVG path centred on (0, 0), about 10 px across
};

inline PlotStyle plot_style(std::size_t line) {
  static constexpr const char* kColours[] = {"#d62728", "#1f77b4", "#2ca02c", "#ff7f0e", "#9467bd",
                                             "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  static constexpr const char* kMarkers[] = {
      "M-4,-4h8v8h-8z",                          // square
      "M0,-5L5,4H-5z",                           // triangle
      "M0,-5L5,0L0,5L-5,0z",                     // diamond
      "M-5,-1.5h10v3h-10z M-1.5,-5h3v10h-3z",    // plus
      "M-4,0a4,4 0 1,0 8,0a4,4 0 1,0 -8,0",      // circle
      "M0,5L5,-4H-5z",                           // triangle, down
      "M-5,-5L5,5M5,-5L-5,5",                    // x (stroked)
      "M-5,-2h10v4h-10z",                        // bar
      "M0,-5L1.5,-1.5L5,0L1.5,1.5L0,5L-1.5,1.5L-5,0L-1.5,-1.5z",  // star
      "M-4,-4h8v3h-8z M-4,1h8v3h-8z",            // two bars
  };
  return {kColours[line % std::size(kColours)], kMarkers[line % std::size(kMarkers)]};
}

/// The marker of `style` at (x, y), filled and outlined in its colour.
template <class Out>
void draw_marker(Out& svg, const PlotStyle& style, double x, double y) {
  svg << "<path d='" << style.marker << "' fill='" << style.colour << "' stroke='" << style.colour
      << "' transform='translate(" << x << ',' << y << ")'/>\n";
}

}  // namespace eco::bench
