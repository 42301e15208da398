#include "common/formats/rtklib_pos_writer.hpp"

#include <cstdio>
#include <memory>

#include "common/io/input_error.hpp"
#include "common/io/output_file.hpp"
#include "common/time/gps_time.hpp"

namespace ldv {

void write_rtklib_pos(const std::string& path, const std::vector<GnssFix>& fixes, const RtklibPosOptions& opt) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw InputError(path, 0, "cannot open file for writing");
  std::FILE* o = f.get();
  std::fprintf(o, "%% program   : %s\n", opt.program.c_str());
  if (!fixes.empty()) {
    const GpsTime a{opt.gps_week, fixes.front().t_s}, b{opt.gps_week, fixes.back().t_s};
    std::fprintf(o, "%% obs start : %s GPST (week%04d %8.1fs)\n", format_rtklib_time(a, 1).c_str(), a.week, a.sow_s);
    std::fprintf(o, "%% obs end   : %s GPST (week%04d %8.1fs)\n", format_rtklib_time(b, 1).c_str(), b.week, b.sow_s);
  }
  std::fprintf(o, "%% pos mode  : Kinematic\n%% amb res   : Instantaneous\n");
  for (const auto& c : opt.comments) std::fprintf(o, "%% %s\n", c.c_str());
  std::fprintf(o, "%%\n%% (lat/lon/height=WGS84/ellipsoidal,Q=1:fix,2:float,3:sbas,4:dgps,5:single,6:ppp,ns=# of satellites)\n");
  std::fprintf(o, "%%  GPST                  latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   sde(m)   sdu(m)  "
                  "sdne(m)  sdeu(m)  sdun(m) age(s)  ratio");
  if (opt.with_velocity)
    std::fprintf(o, "    vn(m/s)    ve(m/s)    vu(m/s)      sdvn     sdve     sdvu    sdvne    sdveu    sdvun");
  std::fprintf(o, "\n");
  for (const GnssFix& g : fixes) {
    const std::string t = format_rtklib_time(GpsTime{opt.gps_week, g.t_s}, 3);
    std::fprintf(o, "%s %14.9f %14.9f %10.4f %3d %3d %8.4f %8.4f %8.4f %8.4f %8.4f %8.4f %6.2f %6.1f", t.c_str(),
                 g.pos.lat_rad * kRadToDeg, g.pos.lon_rad * kRadToDeg, g.pos.h_m, static_cast<int>(g.quality), g.num_sats,
                 g.pos_std_ned_m.x(), g.pos_std_ned_m.y(), g.pos_std_ned_m.z(), 0.0, 0.0, 0.0, g.age_s, g.ratio);
    if (opt.with_velocity)
      std::fprintf(o, " %10.5f %10.5f %10.5f %8.5f %8.5f %8.5f %8.5f %8.5f %8.5f", g.vel_n_mps.x(), g.vel_n_mps.y(),
                   -g.vel_n_mps.z(), g.vel_std_n_mps.x(), g.vel_std_n_mps.y(), g.vel_std_n_mps.z(), 0.0, 0.0, 0.0);
    std::fprintf(o, "\n");
  }
  close_checked(f.release(), path);  // buffered data meets a full disk only here
}

}  // namespace ldv
