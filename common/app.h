#pragma once
// The program around a chapter: command line, context, scene, camera, the frame loop for
// the window and for headless runs, the panel, and the outputs (PNG, --bench JSON,
// --check against the reference images). A chapter's main() reads:
//
//   return lp::run_chapter(argc, argv, kChapter, [](lp::App& app) {
//     MyStage stage(app.scene_gpu());
//     while (app.next_frame()) {
//       const lp::Frame& f = app.frame();
//       { auto pass = app.metrics().pass("lighting"); stage.render(f); }
//       app.panel([&] { /* chapter controls */ });
//     }
//   });
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/camera.h"
#include "common/cli.h"
#include "common/context.h"
#include "common/image.h"
#include "common/measure.h"
#include "common/metrics.h"
#include "common/number_answer.h"
#include "common/scene.h"
#include "common/scene_gpu.h"
#include "common/target.h"

namespace lp {

// [minified-texture-allowance]
// A view that samples a texture minified far into the distance (the atrium's tiled floor)
// reads a mip level OpenGL leaves to the implementation, and a surface's highlight can magnify
// a different texel into tens of steps: on a renderer other than the references' such a view
// may fail on up to 2 % of its pixels (README.md, "Is my build right?"; the chapters' books
// quote what the H200 measured). The renderer that made the references keeps 0.1 %.
inline constexpr CompareOptions kMinifiedTextureAllowance{.threshold = 3, .max_failing_fraction = 0.02};
// [/minified-texture-allowance]
// A picture of counts per pixel (chapter 03's fragments shaded) changes at every volume's edge,
// and OpenGL leaves the rule for a pixel centre on an edge to the implementation: on another
// renderer such an edge may land one pixel over (CompareOptions::edge_radius). The renderer
// that made the references keeps every pixel.
inline constexpr CompareOptions kMovedEdgeAllowance{.threshold = 3, .max_failing_fraction = 0.001, .edge_radius = 1};

// One reference image: a view, a mode and knob values, compared with a tolerance.
struct Shot {
  std::string view;
  std::string mode;
  std::map<std::string, double> knobs = {};
  CompareOptions tolerance = {};  // against the renderer that made the references
  // On another renderer (a reader's GPU), where OpenGL leaves a result to the implementation
  // (e.g. which mip level a minified texel reads): the allowance that difference needs.
  // Unset: the same tolerance everywhere.
  std::optional<CompareOptions> other_renderer = {};
  // File name stem: "<view>_<mode>[_<knob><value>...]", a choice knob as "_<knob>-<name>".
  std::string name(const CliSpec& spec) const;
};

// An exercise: one function of the chapter's shaders, written by the reader. With `--exercise K`
// every program is built with the define `define "path of the reader's file"`, and the chapter's
// shader takes that file in place of its own function:
//   #ifdef EXERCISE_BLINN_PHONG
//   #include EXERCISE_BLINN_PHONG
//   #else
//   ... the chapter's own function ...
//   #endif
// The stub is chapters/<program>/exercises/<file> (LIGHTPASS_EXERCISE_DIR names another folder:
// the tests point it at exercises/solutions/, whose files answer them); `--check` compares its
// shots with tests/reference/<program>/exercises/, made from the solutions.
struct Exercise {
  std::string title;        // what to write, in a few words
  std::string file;         // the stub's name, the same in exercises/ and exercises/solutions/
  std::string define;       // the name the chapter's shader tests with #ifdef and includes
  std::vector<Shot> shots;  // what --check renders, at the chapter's exercise size
  std::string look_at;      // where a wrong answer shows, said when the check fails
  std::string scene = {};   // the scene its shots are of, when not the chapter's default
  // An answer that is a number (common/number_answer.h): `file` is a text file with the line
  // `answer = ...`, no define and no shots; --check compares the number, with no context.
  std::optional<NumberAnswer> number = {};
};

struct Chapter {
  CliSpec cli;
  std::vector<Shot> references;  // what --check renders for the default scene, at the reference size
  // Other scenes with references of their own (a Shot names a view, not a scene), by the path
  // given to --scene: `--check --scene assets/atrium/atrium.gltf` renders the atrium's.
  std::map<std::string, std::vector<Shot>> scene_references = {};
  int reference_width = 320, reference_height = 180;
  std::vector<Exercise> exercises = {};  // --exercise K is exercises[K - 1]
  int exercise_width = 160, exercise_height = 90;
  // The shots of `scene` (matched by file name); throws Error when it has none.
  const std::vector<Shot>& references_for(const std::string& scene) const;
  std::vector<std::string> reference_scenes() const;  // the default scene first
};

// What the chapter needs to draw one frame.
struct Frame {
  int width = 0, height = 0;
  FrameCamera camera;
  std::string mode;
  std::map<std::string, double> knobs;
  GLuint target = 0;           // framebuffer: sRGB colour + depth/stencil, width x height
  std::uint64_t index = 0;     // frames since start
  bool reload_shaders = false; // R pressed in the window: rebuild programs from disk
  // Seconds since the last frame: the real time in a window (at most 0.1), 1/60 headless,
  // so N headless frames always simulate N/60 s.
  float dt = 1.f / 60.f;
  // The first frame of a new image: headless, each image (--check shot, --bench, the PNG);
  // in a window, the first frame and each change of mode or view. State that builds up over
  // frames (eye adaptation) starts again here.
  bool new_shot = true;
  void bind_output() const;    // target, the viewport, sRGB encoding of linear output
  double knob(const std::string& name) const;
  int knob_int(const std::string& name) const { return static_cast<int>(knob(name)); }
  const std::string& choice(const std::string& name) const;  // a choice knob's name
  const CliSpec* spec = nullptr;  // the chapter's, for choice()
};

class App {
 public:
  App(const Chapter& chapter, Options options);
  ~App();

  const Options& options() const { return options_; }
  const Scene& scene() const { return *scene_; }
  const SceneGpu& scene_gpu() const { return *scene_gpu_; }
  Context& context() { return *context_; }
  PassMetrics& metrics() { return metrics_; }
  // Where a chapter prints what a headless run did (lights drawn, fragments shaded): standard
  // output, quiet in a window and under --check and --bench, whose output is their own.
  std::ostream& report();

  // Advances the loop: finishes the previous frame (present, read back, compare) and
  // prepares the next. False when the window closed or the headless work is done.
  bool next_frame();
  const Frame& frame() const { return frame_; }
  // The side panel (window only): frame time, mode, view, knobs, then the chapter's
  // controls, then the passes' timings.
  void panel(const std::function<void()>& chapter_controls = {});
  // Inside panel()'s chapter controls: one line of a plan of stages. With `knob` (an on/off
  // knob of the chapter) a checkbox that switches the stage; without, plain text: the stage
  // is not switched here. `why` says why a stage does not run.
  void plan_line(const std::string& stage, bool runs, const std::string& why, const std::string& knob = {});
  // Writes what the run produced and returns the exit code.
  int finish();
  // Window only: the reader picked another of the chapter's scenes in the panel, so
  // next_frame() returned false. Loads it (a scene that fails to load is reported and the
  // current one kept) and returns true: run the chapter's body again. False otherwise.
  bool switch_scene();

 private:
  struct Job;  // one image to render headless (a shot, or the default view)
  void prepare_frame(int width, int height, const Camera& camera);
  void finish_job(const Job& job);
  void present();
  void fly_to(const Camera& camera);
  void print_bench(const Measurement& m) const;
  void handle_keys(const std::vector<int>& keys);  // Esc, R, P, in the order pressed
  void save_snapshot();                             // P
  void report_reload();                             // after a frame that reloaded the shaders
  std::pair<std::string, std::string> frame_times() const;  // the panel's CPU and GPU lines
  void say(const std::string& message);             // standard output and the panel's status line
  void knob_changed(const Knob& knob);              // the panel changed a knob: say the command line
  std::filesystem::path reference_dir() const;      // tests/reference/<program>/ (exercises/ under it for --exercise)
  int finish_exercise_check();

  Chapter chapter_;
  Options options_;
  std::unique_ptr<Context> context_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<SceneGpu> scene_gpu_;
  PassMetrics metrics_;
  Frame frame_;
  FlyCamera fly_;
  std::vector<Job> jobs_;
  size_t job_ = 0;
  int job_frame_ = 0;
  bool started_ = false, panel_drawn_ = false;
  int failures_ = 0, missing_ = 0;
  const Exercise* exercise_ = nullptr;  // --exercise K
  std::string exercise_path_;           // the file that stands in for the chapter's function
  double last_time_ = 0;
  std::string view_;
  std::string scene_request_, scene_error_;  // the panel's scene choice; why it did not load
  std::string test_scene_;  // tests: LIGHTPASS_TEST_SWITCH_SCENE, picked as if in the panel
  std::string last_mode_;
  bool view_changed_ = false;
  bool reload_pending_ = false;  // R pressed: the chapter reloads this frame; report_reload() says how it went
  std::string status_;           // the panel's last message (P, R)
  double status_time_ = 0;
  int slow_frame_ms_ = 0;        // tests: LIGHTPASS_TEST_SLOW_FRAME_MS, sleep per window frame
  // Where the window shows the image: right of the open panel at the window's aspect when
  // that leaves it at least half the window's width, else the whole window under the panel.
  struct Rect { int x = 0, y = 0, w = 0, h = 0; };
  Rect image_rect(int window_w, int window_h) const;
  Rect image_ = {};
  bool panel_open_ = true;       // as the last frame drew it (the first frame: open)
  double cpu_frame_ms_ = 0;      // wall clock between frames, smoothed
  double gpu_frame_ms_ = -1;     // GL timestamps around the chapter's frame, smoothed; <0 unknown
  struct FrameTimer;
  std::unique_ptr<FrameTimer> gpu_timer_;
  std::unique_ptr<OutputTarget> target_;
  std::unique_ptr<MeasureLoop> bench_;  // the --bench job being measured
  struct Gui;
  std::unique_ptr<Gui> gui_;
};

// Parses the command line, builds the App and runs `body`; prints errors and returns the
// exit code: 0 fine, 1 an error (message says what and where), 2 bad usage.
int run_chapter(int argc, const char* const* argv, const Chapter& chapter, const std::function<void(App&)>& body);

// The exercises, one line each ("  1  Blinn's ... (exercises/blinn_phong.glsl)"), for --help and --list.
std::string exercise_list(const Chapter& chapter);

// out/<name> under the source root (created), for default outputs.
std::string default_output(const std::string& file);

}  // namespace lp
