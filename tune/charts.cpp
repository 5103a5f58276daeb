#include "tune/charts.h"

#include <cstdio>
#include <sstream>

#include "sim/output/atomic_file.h"

namespace occsim::tune {
namespace {

constexpr int kCurvePoints = 101;

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string axisLabel(const TunableParameter& p) {
    return std::string(p.name) +
           (!p.unit.empty() ? std::string(" (") + p.unit + ")" : std::string());
}

std::string runsData(const ChartInput& in, const std::vector<Sample>& runs,
                     const std::vector<double>& objective) {
    std::ostringstream out;
    out << "# run";
    for (const TunableParameter& p : in.space.parameters) out << ' ' << p.name;
    out << " objective_ratio\n";
    for (size_t i = 0; i < runs.size(); ++i) {
        out << i;
        for (double v : runs[i].run->values) out << ' ' << num(v);
        out << ' ' << num(objective[i]) << '\n';
    }
    return out.str();
}

// The response along parameter j, the others at the tuned point.
std::string curveData(const ChartInput& in, size_t j) {
    std::ostringstream out;
    out << "# " << in.space.parameters[j].name << " predicted_ratio lower upper\n";
    Point x = in.tuned;
    for (int k = 0; k < kCurvePoints; ++k) {
        x[j] = static_cast<double>(k) / (kCurvePoints - 1);
        const Prediction p = in.response.predict(x);
        out << num(in.space.value(j, x[j])) << ' ' << num(p.mean) << ' ' << num(p.mean - p.stddev)
            << ' ' << num(p.mean + p.stddev) << '\n';
    }
    return out.str();
}

std::string costData(const ChartInput& in) {
    std::ostringstream out;
    out << "# measured_ms predicted_ms\n";
    for (const LoggedRun& r : in.runs) {
        for (const FrameCounts& f : r.frames)
            out << num(f.frame_ms) << ' ' << num(in.cost.predict(f)) << '\n';
    }
    return out.str();
}

GnuplotChart parameterChart(const ChartInput& in, size_t j) {
    const TunableParameter& p = in.space.parameters[j];
    const std::string data = "tune-curve-" + std::string(p.name) + ".dat";
    const double paper = p.paper_value;
    const double tuned = in.space.value(j, in.tuned[j]);
    // "paper" for the statistical culler, "default" for any other (referenceLabel()).
    const std::string ref = referenceLabel(*in.space.algorithm);
    std::ostringstream b;
    b << "set title \"" << p.name << ": " << in.objective_name
      << " frame time of each sample / that of the " << ref
      << " values in the same run\\nthe fitted "
         "response along "
      << p.name << ", the other parameters at their tuned values"
      << (in.kept_at_paper[j] ? "\\n(no effect beyond noise: kept at the " + ref + " value)" : "")
      << "\"\n"
      << "set xlabel '" << axisLabel(p) << "'\nset ylabel '" << in.objective_name
      << " frame time / " << ref
      << " (same run)'\nset grid\nset key outside right top Left reverse\n"
      << "set lmargin at screen 0.08\nset rmargin at screen 0.72\n"
      << "set offsets graph 0, graph 0, graph 0.08, graph 0.08\n"
      << "set arrow 1 from " << num(paper) << ", graph 0 to " << num(paper)
      << ", graph 1 nohead dt 2 lw 1.5 lc rgb '#7f7f7f'\n"
      << "set arrow 2 from " << num(tuned) << ", graph 0 to " << num(tuned)
      << ", graph 1 nohead lw 2 lc rgb '#d62728'\n"
      << "plot '" << data
      << "' using 1:3:4 with filledcurves fc rgb '#c6dbef' fs solid 0.6 title 'fit +/- 1 sd', \\\n"
      << "     '" << data
      << "' using 1:2 with lines lw 2 lc rgb '#1f77b4' title 'fitted response', \\\n"
      << "     'tune-samples.dat' using " << (j + 2) << ":" << (in.space.size() + 2)
      << " with points pt 7 ps 1.2 lc rgb '#ff7f0e' title 'samples', \\\n"
      << "     'tune-references.dat' using " << (j + 2) << ":" << (in.space.size() + 2)
      << " with points pt 6 ps 1.2 lc rgb '#555555' title 'reference runs', \\\n"
      << "     1 with lines dt 3 lc rgb '#000000' title '" << ref << " values (= 1)', \\\n"
      << "     NaN with lines dt 2 lw 1.5 lc rgb '#7f7f7f' title '" << ref << ": " << num(paper)
      << "', \\\n"
      << "     NaN with lines lw 2 lc rgb '#d62728' title 'tuned: " << num(tuned) << "'\n";
    return {"tune-" + std::string(p.name), 1100, 600, b.str()};
}

GnuplotChart costChart() {
    std::ostringstream b;
    b << "set title 'Cost model: every fitted frame, measured against predicted'\n"
      << "set xlabel 'predicted frame time (ms)'\nset ylabel 'measured frame time (ms)'\nset grid\n"
      << "set key top left\nset size ratio -1\n"
      << "plot 'tune-cost-model.dat' using 2:1 with points pt 7 ps 0.5 lc rgb '#1f77b4' title "
         "'frames', \\\n"
      << "     x with lines lc rgb '#d62728' title 'measured = predicted'\n";
    return {"tune-cost-model", 800, 800, b.str()};
}

}  // namespace

PlotResult writeTuneCharts(const ChartInput& in, const std::filesystem::path& out_dir) {
    std::filesystem::create_directories(out_dir);
    writeFileAtomically(out_dir / "tune-samples.dat", runsData(in, in.samples, in.objective));
    writeFileAtomically(out_dir / "tune-references.dat",
                        runsData(in, in.references, in.reference_objective));
    writeFileAtomically(out_dir / "tune-cost-model.dat", costData(in));
    std::vector<GnuplotChart> charts;
    for (size_t j = 0; j < in.space.size(); ++j) {
        writeFileAtomically(
            out_dir / ("tune-curve-" + std::string(in.space.parameters[j].name) + ".dat"),
            curveData(in, j));
        charts.push_back(parameterChart(in, j));
    }
    charts.push_back(costChart());
    return renderCharts(charts, out_dir, "tune.gp");
}

}  // namespace occsim::tune
