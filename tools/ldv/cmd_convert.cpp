// `ldv convert NAV --to gpx|kml|nmea|csv --out FILE [--rate HZ]`: an `ldv nav` solution in the formats other tools
// read (toolbox/convert/track_formats.hpp): GPX 1.1, KML (Google Earth: coloured by GNSS-aided / INS-only, a
// placemark per INS-only span), NMEA 0183 (GGA, RMC, GST, VTG, HDT) and CSV with a header naming every column and
// its unit. The run's FILE_std.txt and FILE_innovations.txt beside the .nav, when present, give the position sigma
// (GST, CSV) and where the INS ran alone.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>

#include "common/io/input_error.hpp"
#include "common/io/number_text.hpp"
#include "common/io/output_file.hpp"
#include "toolbox/convert/track_formats.hpp"
#include "tools/ldv/cli_checks.hpp"
#include "tools/ldv/command_registry.hpp"

namespace {
using namespace ldv;

struct ConvertArgs {
  std::string nav, to, out, talker = "GN";
  double rate_hz = -1.0;  // < 0: the format's default
  int week = -1;
  bool quiet = false;
};

void run_convert(const ConvertArgs& a) {
  convert::TrackOptions options;
  // A receiver's 1 Hz for the track formats; every solution epoch for CSV.
  options.rate_hz = a.rate_hz >= 0.0 ? a.rate_hz : (a.to == "csv" ? 0.0 : 1.0);
  options.week = a.week;
  const convert::SolutionTrack track = convert::load_solution_track(a.nav, options);
  std::ofstream out(a.out, std::ios::binary);  // NMEA's CR LF as written
  if (!out) throw InputError(a.out, 0, "cannot open for writing");
  if (a.to == "gpx") convert::write_gpx(track, out);
  if (a.to == "kml") convert::write_kml(track, out);
  if (a.to == "csv") convert::write_csv(track, out);
  if (a.to == "nmea") convert::write_nmea(track, out, convert::NmeaOptions{a.talker});
  close_checked(out, a.out);
  if (a.quiet) return;
  long ins_only = 0;
  for (const convert::TrackPoint& p : track.points) ins_only += p.aiding == convert::Aiding::kInsOnly;
  std::fprintf(stderr, "ldv convert: %zu points (%s) -> %s (%s)%s%s\n", track.points.size(),
               options.rate_hz > 0.0 ? (six_significant(options.rate_hz) + " Hz").c_str() : "every epoch",
               a.out.c_str(), a.to.c_str(), track.std_path.empty() ? "; no _std.txt beside it: no sigma" : "",
               track.innovations_path.empty()
                   ? "; no _innovations.txt beside it: GNSS-aided and INS-only not told apart"
                   : ("; " + std::to_string(ins_only) + " INS-only").c_str());
}

void add_convert_command(CLI::App& app) {
  auto a = std::make_shared<ConvertArgs>();
  CLI::App* c = app.add_subcommand("convert", "an ldv nav solution as GPX, KML, NMEA or CSV for other tools");
  c->add_option("nav", a->nav,
                "the solution (.nav of ldv nav / ldv smooth; its _std.txt and _innovations.txt beside it are used)")
      ->required();
  c->add_option("--to", a->to, "gpx | kml | nmea | csv")
      ->required()
      ->check(CLI::IsMember({"gpx", "kml", "nmea", "csv"}));
  c->add_option("--out", a->out, "output file")->required();
  c->add_option("--rate", a->rate_hz,
                "points per second on a regular grid of GPS time, interpolated (0: every solution epoch; default 1 for "
                "gpx, kml and nmea, every epoch for csv)")
      ->check(ldv::cli::finite_range(0.0, 1000.0));
  c->add_option("--week", a->week, "GPS week of a .nav whose rows carry none (week 0: KF-GINS files)")
      ->check(CLI::Range(1, 9999));
  c->add_option("--talker", a->talker, "NMEA talker ID (default GN)")->check([](const std::string& t) {
    return t.size() == 2 ? std::string() : std::string("two characters, e.g. GP");
  });
  c->add_flag("--quiet", a->quiet, "no summary on stderr");
  c->callback([a] { run_convert(*a); });
}

const ldv::cli::RegisterCommand kRegisterConvertCommand{"convert", &add_convert_command};
}  // namespace
