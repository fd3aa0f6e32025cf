// How fast the ray-traced ground truth is on this machine's CPU: primary rays (closest
// hit, every attribute) and ambient-occlusion rays (any hit, cosine-weighted, of length
// --radius, from every primary hit) per second, on the atrium and the street. Writes
// 00_raytrace_<machine>.csv naming the CPU and its cores; the book's introduction quotes it.
//
//   raytrace_bench [--out DIR] [--size WxH] [--samples N] [--radius METRES] [--threads N]
//                  [--seconds S] [--machine NAME] [--images DIR]
#include <cctype>
#include <chrono>
#include <ctime>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include <embree3/rtcore_config.h>

#include "common/cli.h"
#include "common/error.h"
#include "common/paths.h"
#include "common/raytrace.h"
#include "common/sweep.h"
#include "tests/unit/raytrace_ao.h"  // the tests' small AO estimator: a realistic ray load

namespace {

using namespace lp;
using Clock = std::chrono::steady_clock;

struct Settings {
  std::string out = (source_root() / "book" / "figures").string();
  int width = 320, height = 180;
  int samples = 16;
  std::string radius = "1";
  int threads = 0;  // every core
  int seconds = 2;  // at least this long per measurement, for a steady number
  std::string machine;
  std::string images;  // where to write each scene's AO image as a PNG (to look at); empty: none
};

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      std::string name = line.substr(line.find(':') + 1);
      name.erase(0, name.find_first_not_of(" \t"));
      return name;
    }
  return "unknown CPU";
}

// "AMD EPYC 7763 64-Core Processor", 2 -> "amd-epyc-7763-64-core-processor-2-cores"
std::string slug(const std::string& cpu, int cores) {
  std::string s;
  for (char c : cpu + " " + std::to_string(cores) + " cores") {
    if (std::isalnum(static_cast<unsigned char>(c))) s += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    else if (!s.empty() && s.back() != '-') s += '-';
  }
  while (!s.empty() && s.back() == '-') s.pop_back();
  return s;
}

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// CPU time of every thread of the process: on a shared machine the wall clock counts the
// other processes' turns too, the CPU time only ours.
double process_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Measured {
  double rays = 0, wall_s = 0, cpu_s = 0;
};

// Runs `work` (which returns the rays it traced) until `min_seconds` have passed, after one
// untimed run (first-touch page faults, thread start-up).
Measured measure(double min_seconds, const std::function<double()>& work) {
  work();
  Measured m;
  Clock::time_point start = Clock::now();
  double cpu_start = process_cpu_seconds();
  do {
    m.rays += work();
    m.wall_s = seconds_since(start);
  } while (m.wall_s < min_seconds);
  m.cpu_s = process_cpu_seconds() - cpu_start;
  return m;
}

struct Row {
  std::string scene, view;
  std::size_t triangles = 0;
  double build_ms = 0, occlusion = 0;
  Measured primary, ao;
};

Row bench(const Settings& s, float radius, const std::string& file, const std::string& view) {
  Scene scene = load_scene(from_root(file));
  Row row{file, view};
  Clock::time_point start = Clock::now();
  RayScene rays(scene);
  row.build_ms = 1000 * seconds_since(start);
  row.triangles = rays.triangle_count();
  FrameCamera camera = frame_camera(scene.camera(view), float(s.width) / s.height);

  std::vector<std::optional<Hit>> hits;
  row.primary = measure(s.seconds, [&] {
    hits = primary_hits(rays, camera, s.width, s.height, s.threads);
    return double(hits.size());
  });
  auto points = surface_points(hits);
  std::size_t seen = 0;
  for (const auto& p : points) seen += p.has_value();
  if (seen == 0) throw Error(file + " view " + view + ": the camera sees nothing to trace from");

  ImageF ao;
  row.ao = measure(s.seconds, [&] {
    ao = trace_image(s.width, s.height, 1, 1, [&](int x, int y, Pcg32& rng, float* out) {
      if (const auto& p = points[std::size_t(y) * s.width + x])
        out[0] = float(test::occluded_rays(rays, *p, radius, s.samples, rng)) / float(s.samples);
    }, s.threads);
    return double(seen) * s.samples;
  });
  if (!s.images.empty()) {
    ImageF visibility = ao;
    for (float& v : visibility.data) v = 1 - v;  // white: open, black: occluded; sky white
    save_png(s.images + "/" + std::filesystem::path(file).stem().string() + "_" + view + "_ao.png", to_srgb8(visibility));
  }
  for (float v : ao.data) row.occlusion += v;
  row.occlusion /= double(seen);  // a sanity check in the CSV: 0 would mean no ray hit anything
  return row;
}

void run(const Settings& s) {
  float radius = 0;
  try {
    radius = std::stof(s.radius);
  } catch (const std::exception&) {
  }
  if (!(radius > 0 && radius < 1e6f)) throw UsageError("--radius must be a length in metres above 0, not '" + s.radius + "'");
  if (s.samples < 1 || s.seconds < 1) throw UsageError("--samples and --seconds must be at least 1");
  check_image_size(s.width, s.height, "--size");

  const std::string cpu = cpu_model();
  const int cores = available_cores(), threads = s.threads == 0 ? cores : s.threads;
  const std::string machine = s.machine.empty() ? slug(cpu, cores) : s.machine;
  std::filesystem::create_directories(s.out);
  const std::string path = s.out + "/00_raytrace_" + machine + ".csv";
  std::ofstream csv(path);
  if (!csv) throw Error("cannot write " + path);
  csv << "# Embree " << RTC_VERSION_STRING << ", primary rays: closest hit with attributes; AO rays: any hit, "
      << s.samples << " cosine-weighted per pixel, length " << s.radius << " m\n"
      << "# mrays_per_s: by the wall clock (what a run takes here, other processes included); "
         "mrays_per_cpu_s: per second of CPU time of one thread (what one core does when it is ours)\n"
      << "machine,cpu,cores,threads,scene,view,triangles,width,height,ao_samples,ao_radius,build_ms,"
         "primary_rays,primary_s,primary_mrays_per_s,primary_mrays_per_cpu_s,"
         "ao_rays,ao_s,ao_mrays_per_s,ao_mrays_per_cpu_s,mean_occlusion\n";
  for (auto [file, view] : {std::pair{"assets/atrium/atrium.gltf", "overview"}, {"assets/street/street.gltf", "street_level"}}) {
    Row r = bench(s, radius, file, view);
    auto rate = [](const Measured& m) { return m.rays / m.wall_s / 1e6; };
    auto cpu_rate = [](const Measured& m) { return m.rays / m.cpu_s / 1e6; };
    csv << machine << ",\"" << cpu << "\"," << cores << ',' << threads << ',' << r.scene << ',' << r.view << ','
        << r.triangles << ',' << s.width << ',' << s.height << ',' << s.samples << ',' << s.radius << ','
        << std::fixed << std::setprecision(2) << r.build_ms;
    for (const Measured* m : {&r.primary, &r.ao})
      csv << ',' << std::setprecision(0) << m->rays << ',' << std::setprecision(3) << m->wall_s << ',' << rate(*m) << ','
          << cpu_rate(*m);
    csv << ',' << std::setprecision(4) << r.occlusion << '\n';
    csv.unsetf(std::ios::fixed);
    std::cout << file << " (" << r.triangles << " triangles, built in " << r.build_ms << " ms): " << rate(r.primary)
              << " M primary rays/s, " << rate(r.ao) << " M AO rays/s on " << threads << " threads of " << cpu
              << " (per CPU second of one thread: " << cpu_rate(r.primary) << " and " << cpu_rate(r.ao) << ")\n";
  }
  std::cout << "wrote " << path << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  return run_sweep(argc, argv, "raytrace_bench", [&](SweepArgs& args) {
    args.text("--out", s.out).size("--size", s.width, s.height).integer("--samples", s.samples);
    args.text("--radius", s.radius).integer("--threads", s.threads).integer("--seconds", s.seconds);
    args.text("--machine", s.machine).text("--images", s.images);
  }, [&] { run(s); });
}
