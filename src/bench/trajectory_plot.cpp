#include "bench/trajectory_plot.hpp"

#include "bench/plot_style.hpp"

#include <eco/io/error.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace eco::bench {
namespace {

constexpr double kSide = 640, kMargin = 50, kLegend = 170;

}  // namespace

void write_trajectory_plot(const std::filesystem::path& path, const std::string& title,
                           const std::vector<OdometryRun>& runs, std::span<const Eigen::Isometry3d> reference) {
  double lo_x = std::numeric_limits<double>::infinity(), lo_y = lo_x, hi_x = -lo_x, hi_y = -lo_x;
  const auto extend = [&](const Eigen::Isometry3d& p) {
    lo_x = std::min(lo_x, p.translation().x());
    hi_x = std::max(hi_x, p.translation().x());
    lo_y = std::min(lo_y, p.translation().y());
    hi_y = std::max(hi_y, p.translation().y());
  };
  for (const Eigen::Isometry3d& p : reference) extend(p);
  for (const OdometryRun& run : runs) std::ranges::for_each(run.poses, extend);
  if (!(lo_x <= hi_x)) lo_x = lo_y = 0, hi_x = hi_y = 1;
  const double span = std::max({hi_x - lo_x, hi_y - lo_y, 1.0});
  const double scale = (kSide - 2 * kMargin) / span;
  // the path in the middle of the square: a straight drive is a line across its centre, not along an edge
  const double mid_x = 0.5 * (lo_x + hi_x), mid_y = 0.5 * (lo_y + hi_y);
  const auto x_of = [&](double x) { return 0.5 * kSide + (x - mid_x) * scale; };
  const auto y_of = [&](double y) { return 0.5 * kSide - (y - mid_y) * scale; };  // north up
  const auto polyline = [&](std::span<const Eigen::Isometry3d> poses) {
    std::ostringstream points;
    for (const Eigen::Isometry3d& p : poses) points << x_of(p.translation().x()) << ',' << y_of(p.translation().y()) << ' ';
    return points.str();
  };

  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kSide + kLegend << "' height='" << kSide
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << kMargin << "' y='24' font-size='15'>Trajectory from above — " << title << "</text>\n";
  const double bar = std::pow(10.0, std::floor(std::log10(span / 2)));  // a scale bar, a round length
  svg << "<line x1='" << kMargin << "' x2='" << kMargin + bar * scale << "' y1='" << kSide - 20 << "' y2='"
      << kSide - 20 << "' stroke='black' stroke-width='2'/><text x='" << kMargin + bar * scale + 6 << "' y='"
      << kSide - 16 << "'>" << bar << " m</text>\n";
  double legend_y = 60;
  if (!reference.empty()) {
    svg << "<polyline class='reference' fill='none' stroke='black' stroke-dasharray='6,4' stroke-width='1.5' points='"
        << polyline(reference) << "'/>\n<line x1='" << kSide << "' x2='" << kSide + 30 << "' y1='" << legend_y
        << "' y2='" << legend_y << "' stroke='black' stroke-dasharray='6,4'/><text x='" << kSide + 36 << "' y='"
        << legend_y + 4 << "'>reference</text>\n";
    legend_y += 22;
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const PlotStyle style = plot_style(i);
    svg << "<polyline class='estimate' fill='none' stroke='" << style.colour << "' stroke-width='1.5' points='"
        << polyline(runs[i].poses) << "'/>\n";
    const std::size_t every = std::max<std::size_t>(1, runs[i].poses.size() / 12);
    for (std::size_t f = i * every / runs.size(); f < runs[i].poses.size(); f += every) {  // staggered per map
      const Eigen::Vector3d& t = runs[i].poses[f].translation();
      draw_marker(svg, style, x_of(t.x()), y_of(t.y()));
    }
    svg << "<line x1='" << kSide << "' x2='" << kSide + 30 << "' y1='" << legend_y << "' y2='" << legend_y
        << "' stroke='" << style.colour << "' stroke-width='1.5'/>";
    draw_marker(svg, style, kSide + 15, legend_y);
    svg << "<text x='" << kSide + 36 << "' y='" << legend_y + 4 << "'>" << runs[i].map << "</text>\n";
    legend_y += 22;
  }
  svg << "</svg>\n";
  std::ofstream file(path);
  file << svg.str();
  if (!file) throw io::Error(path.string(), "", "cannot be written");
}

}  // namespace eco::bench
