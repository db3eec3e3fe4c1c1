#include "bench/svg_plot.hpp"

#include "bench/plot_style.hpp"

#include <eco/io/error.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace eco::bench {
namespace {

constexpr double kWidth = 900, kHeight = 480;
constexpr double kLeft = 70, kRight = 170, kTop = 40, kBottom = 50;  // margins: axes, legend

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
  // are clipped at the top. Methods whose mean times span a decade or more get a log axis, so
  // that the fastest are not flattened into the bottom either.
  std::sort(all.begin(), all.end());
  const double top = all.empty() ? 1.0 : std::max(1e-3, 1.05 * all[std::size_t(0.995 * double(all.size() - 1))]);
  double fastest = top, slowest = 0.0;
  for (const MethodRun& m : run.methods) {
    double sum = 0.0;
    for (const FrameRecord& r : m.frames) sum += r.update_ms;
    if (m.frames.empty() || sum <= 0.0) continue;
    fastest = std::min(fastest, sum / double(m.frames.size()));
    slowest = std::max(slowest, sum / double(m.frames.size()));
  }
  const bool log_axis = slowest >= 10.0 * fastest;
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  auto x_of = [&](double f) { return kLeft + plot_w * f / double(std::max<std::size_t>(frames - 1, 1)); };
  // linear from 0 by round steps, or log from the decade under the fastest mean's half
  const double step = tick_step(top, 6);
  const double y_max = log_axis ? std::pow(10.0, std::ceil(std::log10(top))) : std::ceil(top / step) * step;
  const double y_min = log_axis ? std::pow(10.0, std::floor(std::log10(fastest / 2))) : 0.0;
  auto y_of = [&](double ms) {
    const double v = std::clamp(ms, y_min, y_max);
    const double share = log_axis ? std::log10(v / y_min) / std::log10(y_max / y_min) : v / y_max;
    return kTop + plot_h * (1.0 - share);
  };
  std::vector<double> y_ticks;
  if (log_axis) {
    for (double decade = y_min; decade < y_max * 1.001; decade *= 10) {
      for (double m : {1.0, 2.0, 5.0}) {
        if (m * decade <= y_max * 1.001) y_ticks.push_back(m * decade);
      }
    }
  } else {
    for (double v = 0; v <= y_max + 1e-9; v += step) y_ticks.push_back(v);
  }

  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidth << "' height='" << kHeight
      << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  svg << "<text x='" << kLeft << "' y='24' font-size='15'>Update time per frame — " << to_string(run.options.workload)
      << " workload, " << run.source << "</text>\n";
  for (double v : y_ticks) {  // grid line, tick and label per step
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
    const PlotStyle style = plot_style(m);
    const std::vector<FrameRecord>& records = run.methods[m].frames;
    svg << "<polyline fill='none' stroke-width='1.5' stroke='" << style.colour << "' points='";
    for (const FrameRecord& r : records) svg << x_of(double(r.frame)) << ',' << y_of(r.update_ms) << ' ';
    svg << "'/>\n";
    const std::size_t every = std::max<std::size_t>(1, records.size() / 10);
    for (std::size_t i = m * every / run.methods.size(); i < records.size(); i += every) {  // staggered
      draw_marker(svg, style, x_of(double(records[i].frame)), y_of(records[i].update_ms));
    }
    const double ly = kTop + 16 + 20 * double(m);
    svg << "<line x1='" << kWidth - kRight + 12 << "' x2='" << kWidth - kRight + 36 << "' y1='" << ly << "' y2='" << ly
        << "' stroke-width='2' stroke='" << style.colour << "'/>";
    draw_marker(svg, style, kWidth - kRight + 24, ly);
    svg << "<text x='" << kWidth - kRight + 42 << "' y='" << ly + 4 << "'>" << run.methods[m].name << "</text>\n";
  }
  svg << "<text x='" << kLeft + 4 << "' y='" << kTop - 6 << "' font-size='11'>" << (log_axis ? "log scale" : "")
      << "</text>\n";
  svg << "</svg>\n";
  std::ofstream out(path);
  out << svg.str();
  if (!out) throw io::Error(path.string(), "", "cannot write the plot");
}

}  // namespace eco::bench
