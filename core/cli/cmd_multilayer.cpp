// `plumage multilayer`: complex reflection of a planar stack through the LocalReflection
// plug-in "multilayer" (the same code path the solvers use).
#include <iomanip>
#include <iostream>
#include <sstream>

#include "plumage/charts.hpp"
#include "commands.hpp"
#include "grid_parse.hpp"
#include "plumage/layer_profile.hpp"
#include "plumage/local_reflection.hpp"

namespace plumage::cli {

namespace {

struct Options {
  std::string stack;
  std::string lambda_nm = "400:700:10";
  std::string theta_deg = "0";
  std::string format = "csv";
  std::string plot;
  std::string model = "multilayer";
};

struct Row {
  double lambda_nm, theta_deg;
  JonesReflection r;
};

void run(AppContext& context, const Options& o) {
  check_output_flag("--plot", o.plot);
  LayerProfile profile;
  try {
    profile = parse_stack_text(o.stack);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--stack: ") + e.what());
  }
  const auto lambdas = parse_wavelengths(o.lambda_nm, "--lambda-nm");
  const auto thetas = parse_samples(o.theta_deg, "--theta-deg");
  for (double t : thetas) {
    if (t < 0 || t > 90) throw UsageError("--theta-deg: angles must be in [0, 90]");
  }
  auto model = context.registry().create_named<LocalReflection>(o.model, ParamView{},
                                                                context.registry().context());
  model->prepare(context.preparation());  // the explicit preparation step of any --model

  std::vector<LocalReflection::Request> requests;
  for (double t : thetas) {
    for (double l : lambdas) requests.push_back({l, {0.0, deg_to_rad(t)}, &profile});
  }
  std::vector<JonesReflection> out(requests.size());
  model->reflect(requests, out);
  std::vector<Row> rows;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    rows.push_back({requests[i].lambda_nm, rad_to_deg(requests[i].incidence.phi_local_rad), out[i]});
  }

  if (!o.plot.empty()) {
    LineChart chart;
    chart.title = describe(profile);
    if (chart.title.size() > 90) chart.title = chart.title.substr(0, 87) + "...";
    chart.x_label = "wavelength (nm)";
    chart.y_label = "reflectance";
    for (const auto& r : rows) {
      std::ostringstream series;
      series << "θ = " << r.theta_deg << "°";
      chart.points.push_back({"R_s (E ⊥ plane of incidence)", series.str(), r.lambda_nm, std::norm(r.r.ss)});
      chart.points.push_back({"R_p (E in plane of incidence)", series.str(), r.lambda_nm, std::norm(r.r.pp)});
    }
    draw_line_chart(chart, o.plot);
  }

  std::cout << std::setprecision(12);
  if (o.format == "json") {
    std::cout << "{\"stack\": \"" << describe(profile) << "\", \"rows\": [\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& r = rows[i];
      std::cout << "  {\"lambda_nm\": " << r.lambda_nm << ", \"theta_deg\": " << r.theta_deg
                << ", \"r_s\": [" << r.r.ss.real() << ", " << r.r.ss.imag() << "], \"r_p\": ["
                << r.r.pp.real() << ", " << r.r.pp.imag() << "], \"R_s\": " << std::norm(r.r.ss)
                << ", \"R_p\": " << std::norm(r.r.pp) << "}" << (i + 1 < rows.size() ? "," : "")
                << "\n";
    }
    std::cout << "]}\n";
  } else {
    std::cout << "# stack: " << describe(profile) << "\n"
              << "# r_s: E-field reflection (s), r_p: H-field reflection (p), referenced to the "
                 "top interface; time convention exp(-i omega t)\n"
              << "lambda_nm,theta_deg,re_r_s,im_r_s,re_r_p,im_r_p,R_s,R_p\n";
    for (const auto& r : rows) {
      std::cout << r.lambda_nm << ',' << r.theta_deg << ',' << r.r.ss.real() << ','
                << r.r.ss.imag() << ',' << r.r.pp.real() << ',' << r.r.pp.imag() << ','
                << std::norm(r.r.ss) << ',' << std::norm(r.r.pp) << '\n';
    }
  }
}

}  // namespace

void add_multilayer_command(CLI::App& app, AppContext& context) {
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("multilayer", "Reflection of a planar layer stack");
  cmd->add_option("--stack", o->stack,
                  "Stack, ambient first: \"air | keratin 300 | {melanin 90 | keratin 100}*6 | air\" "
                  "(thickness in nm)")
      ->required();
  cmd->add_option("--lambda-nm", o->lambda_nm, "Wavelengths, from:to:step or a,b,c")->capture_default_str();
  cmd->add_option("--theta-deg", o->theta_deg, "Angles of incidence in degrees")->capture_default_str();
  cmd->add_option("--format", o->format, "Output format")->check(CLI::IsMember({"csv", "json"}))->capture_default_str();
  cmd->add_option("--plot", o->plot, "Also draw reflectance spectra to this PNG");
  cmd->add_option("--model", o->model, "LocalReflection plug-in type")->capture_default_str();
  cmd->callback([&context, o] { run(context, *o); });
}

}  // namespace plumage::cli
