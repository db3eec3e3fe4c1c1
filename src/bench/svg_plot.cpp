#include "bench/svg_plot.hpp"

#include <eco/io/error.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace eco::bench {
namespace {

constexpr double kWidth = 900, kHeight = 480;
constexpr double kLeft = 70, kRight = 170, kTop = 40, kBottom = 50;  // margins: axes, legend
const char* const kColours[] = {"#d62728", "#ff7f0e", "#1f77b4", "#9467bd", "#2ca02c", "#8c564b", "#e377c2"};

/// A round step for about `ticks` ticks over [0, top].
double tick_step(double top, int ticks) {
  const double raw = top / ticks;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * p >= raw) return m * p;
  }
  return 10 * p;
}

}  // namespace

void write_update_plot(const std::filesystem::path& path, const BenchRun& run) {
  std::size_t frames = 1;
  std::vector<double> all;
  for (const MethodRun& m : run.methods) {
    frames = std::max(frames, m.frames.size());
    for (const FrameRecord& r : m.frames) all.push_back(r.update_ms);
  }
  // Scale to the 99.5th percentile so one slow frame does not flatten the rest; taller points
  // are clipped at the top.
  std::sort(all.begin(), all.end());
  const double top = all.empty() ? 1.0 : std::max(1e-3, 1.05 * all[std::size_t(0.995 * double(all.size() - 1))]);
  const double step = tick_step(top, 6);
  const double y_max = std::ceil(top / step) * step;
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  auto x_of = [&](double f) { return kLeft + plot_w * f / double(std::max<std::size_t>(frames - 1, 1)); };
  auto y_of = [&](double ms) { return kTop + plot_h * (1.0 - std::min(ms, y_max) / y_max); };

  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidth << "' height='" << kHeight
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  svg << "<text x='" << kLeft << "' y='24' font-size='15'>Update time per frame — " << to_string(run.options.workload)
      << " workload, " << run.source << "</text>\n";
  for (double v = 0; v <= y_max + 1e-9; v += step) {  // grid line, tick and label per step
    svg << "<line x1='" << kLeft << "' x2='" << kLeft + plot_w << "' y1='" << y_of(v) << "' y2='" << y_of(v)
        << "' stroke='#ddd'/><line class='y-tick' x1='" << kLeft - 5 << "' x2='" << kLeft << "' y1='" << y_of(v)
        << "' y2='" << y_of(v) << "' stroke='black'/><text class='y-tick-label' x='" << kLeft - 8 << "' y='"
        << y_of(v) + 4 << "' text-anchor='end'>" << v << "</text>\n";
  }
  const double last_frame = double(std::max<std::size_t>(frames - 1, 1));
  const double frame_step = std::max(1.0, tick_step(last_frame, 8));  // whole frames only
  for (double f = 0; f <= last_frame + 1e-9; f += frame_step) {
    const double x = x_of(f), y = kTop + plot_h;
    svg << "<line class='x-tick' x1='" << x << "' x2='" << x << "' y1='" << y << "' y2='" << y + 5
        << "' stroke='black'/><text class='x-tick-label' x='" << x << "' y='" << y + 18
        << "' text-anchor='middle'>" << f << "</text>\n";
  }
  svg << "<rect x='" << kLeft << "' y='" << kTop << "' width='" << plot_w << "' height='" << plot_h
      << "' fill='none' stroke='black'/>\n";
  svg << "<text x='" << kLeft + plot_w / 2 << "' y='" << kHeight - 10 << "' text-anchor='middle'>frame</text>\n";
  svg << "<text transform='translate(18," << kTop + plot_h / 2 << ") rotate(-90)' text-anchor='middle'>update [ms]</text>\n";
  for (std::size_t m = 0; m < run.methods.size(); ++m) {
    const char* colour = kColours[m % std::size(kColours)];
    svg << "<polyline fill='none' stroke-width='1.5' stroke='" << colour << "' points='";
    for (const FrameRecord& r : run.methods[m].frames) svg << x_of(double(r.frame)) << ',' << y_of(r.update_ms) << ' ';
    svg << "'/>\n";
    const double ly = kTop + 16 + 20 * double(m);
    svg << "<line x1='" << kWidth - kRight + 12 << "' x2='" << kWidth - kRight + 36 << "' y1='" << ly << "' y2='" << ly
        << "' stroke-width='3' stroke='" << colour << "'/><text x='" << kWidth - kRight + 42 << "' y='" << ly + 4
        << "'>" << run.methods[m].name << "</text>\n";
  }
  svg << "</svg>\n";
  std::ofstream out(path);
  out << svg.str();
  if (!out) throw io::Error(path.string(), "", "cannot write the plot");
}

}  // namespace eco::bench
