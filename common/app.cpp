#include "common/app.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_internal.h>  // the panel's layout, said for tests (ImGuiWindow)
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <thread>
#include <utility>

#include "common/error.h"
#include "common/input.h"
#include "common/paths.h"
#include "common/shader.h"

namespace lp {

namespace {
constexpr int kBenchFrames = 60;  // measured after measure()'s warm-up (common/measure.h)
constexpr float kPanelWidth = 330;  // pixels: a quarter of a 1280-wide window, the image beside it
constexpr float kPanelMargin = 10;  // pixels around the panel, which stays at the top left

float panel_width(float window_width) { return std::max(160.f, std::min(kPanelWidth, window_width - 2 * kPanelMargin)); }
}  // namespace

namespace {

// The folder of the reader's answers: exercises/ (the stubs), or the one LIGHTPASS_EXERCISE_DIR
// names; the solutions when making the references, which are theirs.
std::filesystem::path exercise_file(const Chapter& chapter, const Exercise& exercise, bool solutions) {
  std::filesystem::path dir = source_root() / "chapters" / chapter.cli.program / "exercises";
  if (solutions) dir /= "solutions";
  else if (const char* d = std::getenv("LIGHTPASS_EXERCISE_DIR"); d && *d) dir = from_root(d);
  const auto path = dir / exercise.file;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw Error("exercise '" + exercise.title + "': no file " + path.string() +
                (solutions || !std::getenv("LIGHTPASS_EXERCISE_DIR") ? "" : " (LIGHTPASS_EXERCISE_DIR names the folder)"));
  return std::filesystem::absolute(path, ec);
}

// tests/reference/<program>/exercises/exercise<K>_<shot>.png
std::string exercise_shot_name(int k, const Shot& shot, const CliSpec& spec) {
  return "exercise" + std::to_string(k) + "_" + shot.name(spec);
}

// An exercise whose answer is a number: the reader's file against the chapter's computation,
// in words; no context is needed. --update-references has nothing to make.
int check_number_exercise(const Chapter& chapter, const Options& options) {
  const Exercise& e = chapter.exercises[std::size_t(options.exercise - 1)];
  const std::string what = "exercise " + std::to_string(options.exercise) + " (" + e.title + ")";
  if (options.update_references) {
    std::cout << what << ": its answer is a number the chapter computes; no images to update\n";
    return 0;
  }
  const std::string path = exercise_file(chapter, e, false).string();
  const NumberVerdict v = check_number_answer(read_answer_file(path), path, *e.number, e.number->expected());
  if (v.right) {
    std::cout << what << ": your answer matches the solution: " << v.words << '\n';
    return 0;
  }
  std::cout << what << ": your answer does not match the solution: " << v.words << ".\n  Look at " << e.look_at
            << ".\n  Your file: " << path << '\n';
  return 1;
}

}  // namespace

std::string exercise_list(const Chapter& chapter) {
  std::ostringstream s;
  for (std::size_t i = 0; i < chapter.exercises.size(); ++i)
    s << "  " << std::setw(2) << i + 1 << "  " << chapter.exercises[i].title << " (chapters/" << chapter.cli.program
      << "/exercises/" << chapter.exercises[i].file << ")\n";
  return s.str();
}

std::string Shot::name(const CliSpec& spec) const {
  std::ostringstream s;
  s << view << '_' << mode;
  for (const auto& [k, v] : knobs) {
    auto knob = std::find_if(spec.knobs.begin(), spec.knobs.end(), [&](const Knob& x) { return x.name == k; });
    if (knob != spec.knobs.end() && !knob->choices.empty()) s << '_' << k << '-' << knob->choice(v);
    else s << '_' << k << v;
  }
  return s.str();
}

void Frame::bind_output() const {
  glBindFramebuffer(GL_FRAMEBUFFER, target);
  glViewport(0, 0, width, height);
  glEnable(GL_FRAMEBUFFER_SRGB);
}

const std::vector<Shot>& Chapter::references_for(const std::string& scene) const {
  const auto file = std::filesystem::path(scene).filename();
  if (file == std::filesystem::path(cli.default_scene).filename()) return references;
  for (const auto& [path, shots] : scene_references)
    if (file == std::filesystem::path(path).filename()) return shots;
  std::string known;
  for (const auto& s : reference_scenes()) known += " " + s;
  throw Error(cli.program + " has no reference images of " + scene + "; scenes with references:" + known);
}

std::vector<std::string> Chapter::reference_scenes() const {
  std::vector<std::string> scenes = {cli.default_scene};
  for (const auto& [path, shots] : scene_references) scenes.push_back(path);
  return scenes;
}

const std::string& Frame::choice(const std::string& name) const {
  for (const auto& k : spec->knobs)
    if (k.name == name && !k.choices.empty()) return k.choice(knob(name));
  throw Error("internal: the chapter reads --" + name + " as a choice, and it is not one");
}

double Frame::knob(const std::string& name) const {
  auto it = knobs.find(name);
  if (it == knobs.end()) throw Error("internal: the chapter reads an undeclared knob --" + name);
  return it->second;
}

std::string default_output(const std::string& file) {
  auto path = source_root() / "out" / file;
  std::filesystem::create_directories(path.parent_path());
  return path.string();
}

struct App::Job {
  enum Kind { Image, Check, Bench } kind = Image;
  Shot shot;
  int width = 0, height = 0, frames = 1;
  std::string out;
};

// Dear ImGui on the GLFW window; exists only in window mode. GLFW's callbacks queue the input
// (common/input.h) and each frame feeds ImGui its share, so a tap or a click shorter than a
// slow frame still reaches the panel and the shortcuts, at the place it happened.
struct App::Gui {
  explicit Gui(GLFWwindow* w) : window(w) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the reader's folder
    ImGui_ImplGlfw_InitForOpenGL(w, false);  // no ImGui callbacks: ours queue the events
    ImGui_ImplOpenGL3_Init("#version 450");
    glfwSetWindowUserPointer(w, this);
    glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int scancode, int action, int mods) {
      of(win).push({.kind = InputEvent::Key, .code = key, .action = action, .scancode = scancode, .mods = mods});
    });
    glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int mods) {
      double x = 0, y = 0;
      glfwGetCursorPos(win, &x, &y);
      of(win).push({.kind = InputEvent::Button, .code = button, .action = action, .mods = mods, .x = x, .y = y});
    });
    glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
      of(win).push({.kind = InputEvent::Move, .x = x, .y = y});
    });
    glfwSetScrollCallback(w, [](GLFWwindow* win, double dx, double dy) {
      of(win).push({.kind = InputEvent::Scroll, .x = dx, .y = dy});
    });
    glfwSetCharCallback(w, [](GLFWwindow* win, unsigned int c) {
      of(win).push({.kind = InputEvent::Char, .code = static_cast<int>(c)});
    });
    glfwSetWindowFocusCallback(w, ImGui_ImplGlfw_WindowFocusCallback);
    glfwSetCursorEnterCallback(w, [](GLFWwindow* win, int entered) {
      ImGui_ImplGlfw_CursorEnterCallback(win, entered);
      // Left the window: the panel is no longer under the cursor (no hover stays behind).
      if (!entered) of(win).push({.kind = InputEvent::Move, .x = -FLT_MAX, .y = -FLT_MAX});
    });
  }
  ~Gui() {
    glfwSetKeyCallback(window, nullptr);
    glfwSetMouseButtonCallback(window, nullptr);
    glfwSetCursorPosCallback(window, nullptr);
    glfwSetScrollCallback(window, nullptr);
    glfwSetCharCallback(window, nullptr);
    glfwSetWindowFocusCallback(window, nullptr);
    glfwSetCursorEnterCallback(window, nullptr);
    glfwSetWindowUserPointer(window, nullptr);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  static InputQueue& of(GLFWwindow* w) { return static_cast<Gui*>(glfwGetWindowUserPointer(w))->queue; }

  // Starts ImGui's frame with the next share of the queue; returns it for the shortcuts.
  FrameInput new_frame() {
    // ImGui finds what is under the cursor among the last frame's windows: in the first frame
    // there are none, so the input waits a frame for the panel to be there.
    FrameInput in = frames++ == 0 ? FrameInput{} : queue.next_frame();
    for (const InputEvent& e : in.events) {
      if (e.kind == InputEvent::Key) ImGui_ImplGlfw_KeyCallback(window, e.code, e.scancode, e.action, e.mods);
      if (e.kind == InputEvent::Char) ImGui_ImplGlfw_CharCallback(window, static_cast<unsigned int>(e.code));
      if (e.kind == InputEvent::Scroll) ImGui_ImplGlfw_ScrollCallback(window, e.x, e.y);
    }
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();  // polls the cursor and buttons as they are now: the queue's state replaces them
    ImGuiIO& io = ImGui::GetIO();
    for (int i = 0; i < IM_ARRAYSIZE(io.MouseDown) && i < int(in.mouse_down.size()); ++i) io.MouseDown[i] = in.mouse_down[i];
    if (in.mouse_known) io.MousePos = ImVec2(static_cast<float>(in.mouse_x), static_cast<float>(in.mouse_y));
    ImGui::NewFrame();
    if (queue.dropped() > reported_drops) {
      std::cerr << "warning: " << queue.dropped() - reported_drops << " input events dropped (more than "
                << InputQueue::kCapacity << " waiting for a slow frame)\n";
      reported_drops = queue.dropped();
    }
    return in;
  }

  GLFWwindow* window;
  InputQueue queue;
  std::size_t reported_drops = 0;
  std::uint64_t frames = 0;
};

// GL timestamps around the chapter's frame (prepare_frame to the blit), read kSlots frames
// later, when they are done, so that the CPU never waits for them.
struct App::FrameTimer {
  FrameTimer() { glCreateQueries(GL_TIMESTAMP, 2 * kSlots, ids); }
  ~FrameTimer() { glDeleteQueries(2 * kSlots, ids); }
  void start() {
    read(slot);
    glQueryCounter(ids[2 * slot], GL_TIMESTAMP);
  }
  void stop() {
    glQueryCounter(ids[2 * slot + 1], GL_TIMESTAMP);
    issued[slot] = true;
    slot = (slot + 1) % kSlots;
  }
  // Milliseconds of the oldest frame, when its queries are done; <0 when none is known yet.
  double last_ms = -1;

 private:
  void read(int s) {
    if (!issued[s]) return;
    GLint done = 0;
    glGetQueryObjectiv(ids[2 * s + 1], GL_QUERY_RESULT_AVAILABLE, &done);
    if (!done) return;  // a frame older still: keep the last value
    GLuint64 a = 0, b = 0;
    glGetQueryObjectui64v(ids[2 * s], GL_QUERY_RESULT, &a);
    glGetQueryObjectui64v(ids[2 * s + 1], GL_QUERY_RESULT, &b);
    last_ms = b > a ? double(b - a) * 1e-6 : 0.0;
    issued[s] = false;
  }
  static constexpr int kSlots = 2;
  GLuint ids[2 * kSlots] = {};
  bool issued[kSlots] = {};
  int slot = 0;
};

App::App(const Chapter& chapter, Options options) : chapter_(chapter), options_(std::move(options)) {
  bool batch = options_.check || options_.bench;
  context_ = Context::create({.headless = options_.headless || batch, .width = options_.width,
                              .height = options_.height, .title = "lightpass " + chapter_.cli.program});
  scene_ = std::make_unique<Scene>(load_scene(resolve_input(options_.scene)));
  for (const auto& w : scene_->warnings) std::cerr << "warning: " << w << '\n';
  // --bench writes JSON on standard output: its notes go with the warnings.
  for (const auto& n : scene_->notes) (options_.bench ? std::cerr : std::cout) << "note: " << n << '\n';
  if (!options_.out.empty()) {
    // --out names a PNG (an image) or, with --check, a folder: a missing folder is made, and said.
    std::filesystem::path dir = options_.check ? std::filesystem::path(options_.out) : std::filesystem::path(options_.out).parent_path();
    std::error_code ec;
    if (!dir.empty() && !std::filesystem::exists(dir, ec)) {
      std::filesystem::create_directories(dir, ec);
      if (ec) throw Error("--out: cannot create the directory '" + dir.string() + "': " + ec.message());
      std::cout << "note: created the directory '" << dir.string() << "' for --out\n";
    }
  }
  view_ = options_.view.empty() ? scene_->cameras.front().name : scene_->camera(options_.view).name;
  scene_gpu_ = std::make_unique<SceneGpu>(*scene_);
  frame_.mode = options_.mode;
  frame_.knobs = options_.knobs;
  frame_.spec = &chapter_.cli;

  // Before the window returns below: a window runs the reader's exercise too, and R reloads it.
  if (options_.exercise > 0) {
    exercise_ = &chapter_.exercises.at(options_.exercise - 1);  // run_chapter checked K
    exercise_path_ = exercise_file(chapter_, *exercise_, options_.update_references).string();
    // The define is a quoted path: a quote or a line break in it would end it early.
    if (exercise_path_.find_first_of("\"\n\r\\") != std::string::npos)
      throw Error("exercise " + std::to_string(options_.exercise) + ": the path " + exercise_path_ +
                  " holds a quote, a backslash or a line break, which a GLSL define cannot carry; move the tree");
    set_program_wide_defines({exercise_->define + " \"" + exercise_path_ + "\""});
    (options_.bench ? std::cerr : std::cout) << "exercise " << options_.exercise << " (" << exercise_->title
                                             << "): " << exercise_path_ << " stands in for the chapter's function\n";
  }
  if (context_->is_window()) {
    // Tests of the panel's scene switch: the scene picked after the second frame.
    if (const char* s = std::getenv("LIGHTPASS_TEST_SWITCH_SCENE")) test_scene_ = s;
    // Tests of input at any frame rate: every frame made this slow (a sleep before the poll).
    if (const char* s = std::getenv("LIGHTPASS_TEST_SLOW_FRAME_MS")) slow_frame_ms_ = parse_integer("LIGHTPASS_TEST_SLOW_FRAME_MS", s, 0, 60000);
    gui_ = std::make_unique<Gui>(context_->window());
    gpu_timer_ = std::make_unique<FrameTimer>();
    fly_to(scene_->camera(view_));
    last_time_ = glfwGetTime();
    return;
  }
  if (options_.check && exercise_) {
    for (const auto& shot : exercise_->shots)
      jobs_.push_back({.kind = Job::Check, .shot = shot, .width = chapter_.exercise_width, .height = chapter_.exercise_height});
  } else if (options_.check) {
    for (const auto& shot : chapter_.references_for(options_.scene)) {
      if (options_.mode_given && shot.mode != options_.mode) continue;
      if (options_.view_given && shot.view != options_.view) continue;
      jobs_.push_back({.kind = Job::Check, .shot = shot, .width = chapter_.reference_width, .height = chapter_.reference_height});
    }
    if (jobs_.empty()) throw Error("no reference image of " + chapter_.cli.program + " matches the given --view/--mode");
  } else {
    Job job{.kind = options_.bench ? Job::Bench : Job::Image,
            .shot = {.view = view_, .mode = options_.mode, .knobs = options_.knobs},
            .width = options_.width, .height = options_.height, .frames = options_.frames,
            .out = options_.out.empty() ? default_output(chapter_.cli.program + ".png") : options_.out};
    if (options_.bench && !options_.frames_given) job.frames = kBenchFrames;
    jobs_.push_back(job);
  }
}

App::~App() = default;

// The window's camera, starting at `camera`, at a speed of a tenth of the scene's size a second.
void App::fly_to(const Camera& camera) {
  const glm::vec3 extent = scene_->bounds_max - scene_->bounds_min;
  fly_ = FlyCamera(camera, std::max(0.5f, glm::length(extent) * 0.1f));
}

std::ostream& App::report() {
  static std::ostream quiet(nullptr);  // a stream without a buffer writes nothing
  const bool batch = context_->is_window() || options_.check || options_.bench;
  return batch ? quiet : std::cout;
}

void App::prepare_frame(int w, int h, const Camera& camera) {
  if (!target_ || target_->width() != w || target_->height() != h) {
    target_ = std::make_unique<OutputTarget>(w, h);
    metrics_.set_allocation("output colour SRGB8_ALPHA8", std::size_t(w) * h * 4);
    metrics_.set_allocation("output depth DEPTH24_STENCIL8", std::size_t(w) * h * 4);
  }
  frame_.width = w;
  frame_.height = h;
  frame_.camera = frame_camera(camera, float(w) / float(h));
  frame_.target = target_->framebuffer();
  target_->bind();  // shaders write linear values; the target stores sRGB
}

bool App::next_frame() {
  if (!context_->is_window()) {
    if (started_) {
      const Job& job = jobs_[job_];
      bool done = false;
      if (bench_) {
        done = !bench_->frame_done();  // ends the frame; throws a pass's OpenGL error
      } else {
        metrics_.end_frame();
        metrics_.throw_if_error();  // an OpenGL error in a pass, reported once, outside any destructor
        done = ++job_frame_ == job.frames;
      }
      if (done) {
        finish_job(job);
        ++job_;
        job_frame_ = 0;
        bench_.reset();
      }
    }
    started_ = true;
    frame_.reload_shaders = false;
    if (job_ >= jobs_.size()) return false;
    const Job& job = jobs_[job_];
    // --bench: the one measurement of common/measure.h (warm-up, then job.frames frames).
    if (job.kind == Job::Bench && !bench_) bench_ = std::make_unique<MeasureLoop>(metrics_, MeasureOptions{.frames = job.frames});
    frame_.mode = job.shot.mode;
    frame_.knobs = options_.knobs;
    for (const auto& [k, v] : job.shot.knobs) frame_.knobs[k] = v;
    frame_.dt = 1.f / 60.f;
    frame_.new_shot = job_frame_ == 0;
    ++frame_.index;
    prepare_frame(job.width, job.height, scene_->camera(job.shot.view));
    return true;
  }

  if (started_) {
    if (!panel_drawn_) panel();
    present();
    metrics_.end_frame();
    metrics_.throw_if_error();
    if (reload_pending_) report_reload();
    if (slow_frame_ms_ > 0) {
      // Said, so that a test sends its input once the panel is on screen.
      // With what the panel shows of the frame times, so a test can hold them to the sleep.
      const auto [cpu_text, gpu_text] = frame_times();
      std::cerr << "test: frame " << frame_.index << " presented (the panel shows " << cpu_text << ", " << gpu_text << ')' << std::endl;
      std::this_thread::sleep_for(std::chrono::milliseconds(slow_frame_ms_));
    }
    context_->swap_and_poll();
  }
  if (!test_scene_.empty() && frame_.index == 2) scene_request_ = std::exchange(test_scene_, {});
  if (!scene_request_.empty()) return false;  // the body ends; switch_scene() loads the scene
  started_ = true;
  panel_drawn_ = false;
  int w = 0, h = 0;
  for (context_->framebuffer_size(w, h); w == 0 || h == 0; context_->framebuffer_size(w, h)) {
    if (context_->should_close()) return false;
    glfwWaitEvents();  // minimised: nothing to draw until the window has pixels again
  }
  if (context_->should_close()) return false;
  GLFWwindow* win = context_->window();
  double now = glfwGetTime();
  const double wall = now - last_time_;
  float dt = static_cast<float>(std::min(wall, 0.1));
  last_time_ = now;
  if (frame_.index > 0) cpu_frame_ms_ = cpu_frame_ms_ > 0 ? 0.9 * cpu_frame_ms_ + 0.1 * wall * 1e3 : wall * 1e3;
  frame_.dt = dt;
  frame_.new_shot = frame_.index == 0 || frame_.mode != last_mode_ || view_changed_;
  last_mode_ = frame_.mode;
  view_changed_ = false;
  frame_.reload_shaders = false;
  const FrameInput input = gui_->new_frame();
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureKeyboard) handle_keys(input.keys_pressed);
  if (!io.WantCaptureMouse) fly_.update(win, dt);
  ++frame_.index;
  image_ = image_rect(w, h);
  prepare_frame(image_.w, image_.h, fly_.camera());
  gpu_timer_->start();  // reads an earlier frame's timestamps when they are done
  if (gpu_timer_->last_ms >= 0) gpu_frame_ms_ = gpu_frame_ms_ >= 0 ? 0.9 * gpu_frame_ms_ + 0.1 * gpu_timer_->last_ms : gpu_timer_->last_ms;
  return true;
}

App::Rect App::image_rect(int w, int h) const {
  const int x = static_cast<int>(2 * kPanelMargin + panel_width(float(w)));
  // A window too narrow for both (a small test window): the image fills it, under the panel.
  if (!panel_open_ || 2 * (w - x) < w) return {0, 0, w, h};
  const int iw = w - x;
  const int ih = std::max(1, static_cast<int>(std::lround(double(iw) * h / w)));
  return {x, (h - ih) / 2, iw, ih};
}

void App::handle_keys(const std::vector<int>& keys) {
  for (int key : keys) {
    if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(context_->window(), GLFW_TRUE);
    if (key == GLFW_KEY_R && !frame_.reload_shaders) {
      take_reload_tally();  // count only what this R reloads
      frame_.reload_shaders = reload_pending_ = true;
    }
    if (key == GLFW_KEY_P) save_snapshot();
  }
}

// P: the image the window shows (without the panel) in a new numbered file, next to --out's
// name or out/<program>.png; never over an earlier one.
void App::save_snapshot() {
  if (!target_) return;  // nothing drawn yet
  const std::filesystem::path base = options_.out.empty() ? default_output(chapter_.cli.program + ".png") : options_.out;
  try {
    const std::filesystem::path path = numbered_path(base);
    save_png(path, target_->read());
    say("P: saved " + path.string() + " (" + std::to_string(target_->width()) + "x" + std::to_string(target_->height()) +
        ", the image without the panel)");
  } catch (const Error& e) {
    say(std::string("P: could not save: ") + e.what());
  }
}

void App::report_reload() {
  reload_pending_ = false;
  const ReloadTally t = take_reload_tally();
  if (t.failed == 0) {
    say("R: reloaded " + std::to_string(t.reloaded) + " shader program" + (t.reloaded == 1 ? "" : "s") + " from disk");
    return;
  }
  // The first failure's first error line names its file and line (common/shader.h); the
  // whole log was printed above.
  std::string first = t.first_error;
  std::istringstream lines(t.first_error);
  for (std::string line; std::getline(lines, line);)
    if (line.find("error") != std::string::npos && line.find(':') != std::string::npos && line.rfind("cannot ", 0) != 0) {
      first = line;
      break;
    }
  if (auto end = first.find('\n'); end != std::string::npos) first = first.substr(0, end);
  say("R: " + std::to_string(t.failed) + " of " + std::to_string(t.failed + t.reloaded) +
      " shader programs failed to build (each kept its previous version): " + first);
}

void App::say(const std::string& message) {
  std::cout << message << std::endl;
  status_ = message;
  status_time_ = glfwGetTime();
}

void App::knob_changed(const Knob& k) {
  metrics_.reset();
  std::cout << "panel: --" << k.name << ' ' << knob_text(chapter_.cli, k.name, frame_.knobs[k.name]) << std::endl;
}

namespace {

std::string tooltip_drawn;  // where this frame's tooltip lies, for the test line (App::panel)

// A tooltip for the item just drawn, wrapped to a readable width, or narrower in a narrow window
// so that the whole tooltip fits in it.
void tooltip(const std::string& text) {
  if (text.empty() || !ImGui::IsItemHovered()) return;
  ImGui::BeginTooltip();
  const float padding = ImGui::GetStyle().WindowPadding.x;  // the wrap is from the tooltip's left edge, text after the padding
  const float fits = ImGui::GetIO().DisplaySize.x - 2 * kPanelMargin - padding;
  ImGui::PushTextWrapPos(std::max(ImGui::GetFontSize() * 8.f, std::min(ImGui::GetFontSize() * 30.f, fits)));
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  const ImVec2 at = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  tooltip_drawn = "; a tooltip at " + std::to_string(int(at.x)) + "," + std::to_string(int(at.y)) + " size " +
                  std::to_string(int(size.x)) + "x" + std::to_string(int(size.y));
  ImGui::EndTooltip();
}

// An on/off knob: integer, 0 or 1, not a choice of names. The panel shows it as a checkbox.
bool is_switch(const Knob& k) { return k.integer && k.choices.empty() && k.min == 0 && k.max == 1; }

}  // namespace

void App::panel(const std::function<void()>& chapter_controls) {
  if (!gui_) return;
  panel_drawn_ = true;
  // Narrow, at the top left, and as tall as the window at most: the image is drawn right of it
  // (image_rect), and what does not fit scrolls. The title bar's triangle folds it away, and
  // the image then fills the window.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(kPanelMargin, kPanelMargin), ImGuiCond_Always);
  const float width = panel_width(display.x);
  ImGui::SetNextWindowSizeConstraints(ImVec2(width, 0), ImVec2(width, std::max(60.f, display.y - 2 * kPanelMargin)));
  ImGui::Begin(chapter_.cli.program.c_str(), nullptr, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoMove);
  if (const bool open = !ImGui::IsWindowCollapsed(); open != panel_open_) {
    panel_open_ = open;
    std::cout << (open ? "panel: opened, the image beside it" : "panel: folded, the image fills the window") << std::endl;
  }
  ImGui::PushItemWidth(ImGui::GetFontSize() * 11.f);
  ImGui::PushTextWrapPos(0.f);  // every line wraps at the panel's edge instead of being cut off there
  tooltip_drawn.clear();
  ImVec4 last_knob;  // the last knob's rectangle, for the test line
  const auto [cpu_text, gpu_text] = frame_times();
  ImGui::TextUnformatted(("frame " + cpu_text).c_str());
  tooltip("CPU: the wall-clock time from one frame to the next, the panel and presenting included.");
  if (gpu_frame_ms_ >= 0) ImGui::TextUnformatted(("      " + gpu_text).c_str());
  else ImGui::TextDisabled("      %s", gpu_text.c_str());
  tooltip(std::string("GPU: GL timestamps around the chapter's frame, the panel left out") +
          (context_->is_software() ? " (llvmpipe renders on the CPU: this is its time)." : "."));
  if (ImGui::CollapsingHeader("about", 0)) {
    ImGui::TextWrapped("%s", chapter_.cli.summary.c_str());
    ImGui::TextWrapped("%s", context_->renderer().c_str());
    ImGui::TextDisabled("W/A/S/D/Q/E move, right mouse looks,");
    ImGui::TextDisabled("R reloads shaders, P saves a PNG, Esc quits");
  }
  ImGui::Separator();
  if (ImGui::BeginCombo("mode", frame_.mode.c_str())) {
    for (const auto& m : chapter_.cli.modes)
      if (ImGui::Selectable(m.c_str(), m == frame_.mode) && m != frame_.mode) {
        frame_.mode = m;
        metrics_.reset();
        std::cout << "panel: --mode " << m << std::endl;
      }
    ImGui::EndCombo();
  }
  tooltip(option_help("mode"));
  // The chapter's scenes (those with references), when it has more than one.
  std::vector<std::string> scenes = chapter_.reference_scenes();
  if (std::find(scenes.begin(), scenes.end(), options_.scene) == scenes.end()) scenes.insert(scenes.begin(), options_.scene);
  if (scenes.size() > 1) {
    if (ImGui::BeginCombo("scene", options_.scene.c_str())) {
      for (const auto& sc : scenes)
        if (ImGui::Selectable(sc.c_str(), sc == options_.scene) && sc != options_.scene) scene_request_ = sc;
      ImGui::EndCombo();
    }
    tooltip(option_help("scene"));
  }
  if (!scene_error_.empty()) ImGui::TextWrapped("%s", scene_error_.c_str());
  if (ImGui::BeginCombo("view", view_.c_str())) {
    for (const auto& c : scene_->cameras)
      if (ImGui::Selectable(c.name.c_str(), c.name == view_)) {
        view_ = c.name;
        view_changed_ = true;
        fly_to(c);
        std::cout << "panel: --view " << c.name << std::endl;
      }
    ImGui::EndCombo();
  }
  tooltip(option_help("view"));
  for (const auto& k : chapter_.cli.knobs) {
    double& v = frame_.knobs[k.name];
    if (!k.choices.empty()) {
      if (ImGui::BeginCombo(k.name.c_str(), k.choice(v).c_str())) {
        for (std::size_t i = 0; i < k.choices.size(); ++i)
          if (ImGui::Selectable(k.choices[i].c_str(), std::size_t(v) == i) && std::size_t(v) != i) {
            v = double(i);
            knob_changed(k);
          }
        ImGui::EndCombo();
      }
    } else if (is_switch(k)) {
      bool on = v != 0;
      if (ImGui::Checkbox(k.name.c_str(), &on)) {
        v = on ? 1 : 0;
        knob_changed(k);
      }
    } else {
      ImGuiSliderFlags flags = k.max > 100 * std::max(1.0, k.min) ? ImGuiSliderFlags_Logarithmic : 0;
      if (k.integer) {
        int i = static_cast<int>(v);
        if (ImGui::SliderInt(k.name.c_str(), &i, int(k.min), int(k.max), "%d", flags)) { v = i; metrics_.reset(); }
      } else {
        float f = static_cast<float>(v);
        if (ImGui::SliderFloat(k.name.c_str(), &f, float(k.min), float(k.max), "%.3g", flags)) v = f;
      }
      // Said once the slider is let go, not at every step of the drag.
      if (ImGui::IsItemDeactivatedAfterEdit()) knob_changed(k);
    }
    last_knob = {ImGui::GetItemRectMin().x, ImGui::GetItemRectMin().y, ImGui::GetItemRectMax().x, ImGui::GetItemRectMax().y};
    tooltip(k.help);
  }
  if (chapter_controls) chapter_controls();
  if (!status_.empty() && glfwGetTime() - status_time_ < 10) {
    ImGui::Separator();
    ImGui::TextWrapped("%s", status_.c_str());
  }
  ImGui::Separator();
  if (ImGui::CollapsingHeader("passes", ImGuiTreeNodeFlags_DefaultOpen) && ImGui::BeginTable("passes", 3, ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch);
    ImGui::TableSetupColumn(context_->is_software() ? "ms (CPU)" : "ms (GPU)");
    ImGui::TableSetupColumn("fragments");
    ImGui::TableHeadersRow();
    for (const auto& st : metrics_.stats()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn(); ImGui::TextWrapped("%s", st.name.c_str());  // a long name wraps in its column
      ImGui::TableNextColumn(); ImGui::Text("%.3f", st.mean_ms);
      ImGui::TableNextColumn(); ImGui::Text("%llu", static_cast<unsigned long long>(st.samples));
    }
    ImGui::EndTable();
  }
  ImGui::Text("render targets: %.1f MB", metrics_.allocated_bytes() / 1e6);
  ImGui::PopTextWrapPos();
  ImGui::PopItemWidth();
  if (slow_frame_ms_ > 0 && !chapter_.cli.knobs.empty()) {
    // Said for tests of the panel (tests/window_panel.sh): where it is, how far it scrolls, how
    // far right its widest line reaches against where its text is cut (clipped), where its last
    // knob is (window pixels) and the tooltip, if one is drawn.
    const ImGuiWindow* w = ImGui::GetCurrentWindow();
    std::cerr << "test: panel at " << int(w->Pos.x) << ',' << int(w->Pos.y) << " size " << int(w->Size.x) << 'x'
              << int(w->Size.y) << ", scrolled " << int(w->Scroll.y) << " of " << int(w->ScrollMax.y) << ", lines reach x "
              << int(std::ceil(w->DC.CursorMaxPos.x)) << " of " << int(std::ceil(w->InnerClipRect.Max.x)) << "; its last knob --"
              << chapter_.cli.knobs.back().name << " at " << int(last_knob.x) << ',' << int(last_knob.y) << " to "
              << int(last_knob.z) << ',' << int(last_knob.w) << tooltip_drawn << std::endl;
  }
  ImGui::End();
}

std::pair<std::string, std::string> App::frame_times() const {
  auto line = [](double ms, const char* unit) {
    char text[96];
    std::snprintf(text, sizeof text, "%.1f ms %s (%.1f fps)", ms, unit, ms > 0 ? 1e3 / ms : 0.0);
    return std::string(text);
  };
  return {line(cpu_frame_ms_, "CPU"), gpu_frame_ms_ >= 0 ? line(gpu_frame_ms_, context_->is_software() ? "llvmpipe" : "GPU")
                                                         : "GPU time: waiting for the first frame"};
}

void App::plan_line(const std::string& stage, bool runs, const std::string& why, const std::string& knob) {
  if (!gui_) return;
  auto k = std::find_if(chapter_.cli.knobs.begin(), chapter_.cli.knobs.end(), [&](const Knob& x) { return x.name == knob; });
  if (k != chapter_.cli.knobs.end() && is_switch(*k)) {
    double& v = frame_.knobs[k->name];
    bool on = v != 0;
    if (ImGui::Checkbox(stage.c_str(), &on)) {
      v = on ? 1 : 0;
      knob_changed(*k);
    }
    tooltip(stage + (runs ? "" : " (not run: " + why + ")") + "\n--" + k->name + ": " + k->help);
  } else {
    // Not switched here: a bullet, not a box, so it does not look clickable. The name wraps
    // (the panel sets the wrap) instead of running past the panel's edge.
    ImGui::Bullet();
    ImGui::SameLine();
    ImGui::TextUnformatted(stage.c_str());
  }
  if (k == chapter_.cli.knobs.end() || !is_switch(*k)) tooltip(stage + (runs ? "" : " (not run: " + why + ")"));
  if (!runs && !why.empty()) {
    ImGui::SameLine();
    ImGui::TextDisabled("(%s)", why.c_str());
  }
}

void App::present() {
  glDisable(GL_FRAMEBUFFER_SRGB);  // copy the stored sRGB bytes as they are: same pixels as headless
  int w = 0, h = 0;
  context_->framebuffer_size(w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDisable(GL_SCISSOR_TEST);  // neither the clear nor the blit is cut by a chapter's scissor
  if (image_.w != w || image_.h != h) {
    // The bars around an image beside the panel.
    glClearColor(0.12f, 0.12f, 0.12f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  // Pixel for pixel (the target is the rectangle's size); GL's rows count from the bottom.
  const int y0 = h - image_.y - image_.h;
  glBlitNamedFramebuffer(target_->framebuffer(), 0, 0, 0, target_->width(), target_->height(), image_.x, y0,
                         image_.x + image_.w, y0 + image_.h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gpu_timer_->stop();
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  ImGui::Render();
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
  if (options_.frames_given && frame_.index >= static_cast<std::uint64_t>(options_.frames)) {
    // Scripted screenshots of the window, panel included (the book's figures of the UI).
    if (!options_.out.empty()) {
      ImageRGBA8 shot = ImageRGBA8::blank(w, h);
      glPixelStorei(GL_PACK_ALIGNMENT, 1);
      glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, shot.pixels.data());
      flip_vertically(shot);
      save_png(options_.out, shot);
      std::cout << "wrote " << options_.out << " (window screenshot, " << w << "x" << h << "; the image " << image_.w << 'x'
                << image_.h << " at " << image_.x << ',' << image_.y << ")\n";
    }
    glfwSetWindowShouldClose(context_->window(), GLFW_TRUE);
  }
}

void App::finish_job(const Job& job) {
  if (GLenum e = glGetError(); e != GL_NO_ERROR)
    throw Error(std::string("OpenGL reported ") + gl::error_name(e) + " while rendering " + job.shot.name(chapter_.cli));
  ImageRGBA8 image = target_->read();
  if (job.kind == Job::Image) {
    save_png(job.out, image);
    std::cout << "wrote " << job.out << " (" << job.width << "x" << job.height << ", view " << job.shot.view
              << ", mode " << job.shot.mode << ", " << context_->renderer() << ")\n";
    return;
  }
  if (job.kind == Job::Bench) {
    print_bench(bench_->result());
    return;
  }
  const std::string name = exercise_ ? exercise_shot_name(options_.exercise, job.shot, chapter_.cli) : job.shot.name(chapter_.cli);
  auto reference = reference_dir() / (name + ".png");
  auto out_dir = options_.out.empty() ? source_root() / "out" / "check" / chapter_.cli.program / (exercise_ ? "exercises" : "")
                                      : std::filesystem::path(options_.out);
  std::filesystem::create_directories(out_dir);
  auto actual_path = out_dir / (name + ".png");
  if (options_.update_references) {
    std::filesystem::create_directories(reference.parent_path());
    save_png(reference, image);
    std::cout << "updated reference " << reference.string() << '\n';
    return;
  }
  if (!std::filesystem::exists(reference)) {
    save_png(actual_path, image);
    std::cout << "MISSING " << name << ": no reference " << reference.string() << " (render kept at "
              << actual_path.string() << "; make references on purpose with --check --update-references)\n";
    ++missing_;
    return;
  }
  // The references were made by one renderer (RENDERER.txt beside them); a different one
  // gets the shot's cross-renderer allowance, where it has one, and is told so.
  CompareOptions tolerance = job.shot.tolerance;
  std::string made_by;
  std::getline(std::ifstream(reference.parent_path() / "RENDERER.txt"), made_by);
  bool other = !made_by.empty() && made_by != context_->renderer();
  if (other && job.shot.other_renderer) tolerance = *job.shot.other_renderer;
  CompareResult r = compare(image, load_png(reference), tolerance);
  std::cout << (r.passed ? "ok       " : "MISMATCH ") << std::left << std::setw(28) << name << ' ' << r.summary()
            << (other && job.shot.other_renderer ? " [other renderer]" : "") << '\n';
  if (!r.passed) {
    ++failures_;
    save_png(actual_path, image);
    auto diff_path = out_dir / (name + "_diff.png");
    // The difference with its key: what each colour means, and where failing starts.
    constexpr int kDiffFullScale = 32;  // diff_heatmap's default
    save_png(diff_path, with_heat_key(diff_heatmap(image, load_png(reference), tolerance.threshold, kDiffFullScale),
                                      {.full_scale = float(kDiffFullScale),
                                       .what = "largest channel difference, 8-bit steps; over " +
                                               std::to_string(tolerance.threshold) + " fails",
                                       .threshold = float(tolerance.threshold)}));
    std::cout << "         actual " << actual_path.string() << "\n         diff   " << diff_path.string()
              << "\n         expected " << reference.string() << '\n';
  }
}

void App::print_bench(const Measurement& m) const {
  nlohmann::ordered_json j;
  j["program"] = chapter_.cli.program;
  j["renderer"] = context_->renderer();
  j["timer"] = m.software                ? "llvmpipe: CPU time with glFinish around each pass"
               : context_->is_software() ? "GL_TIME_ELAPSED queries on llvmpipe (LIGHTPASS_TIMER=queries)"
                                         : "GPU time (GL_TIME_ELAPSED)";
  j["platform"] = context_->platform();
  j["width"] = target_->width();
  j["height"] = target_->height();
  j["scene"] = options_.scene;
  j["view"] = jobs_[job_].shot.view;
  j["mode"] = frame_.mode;
  j["knobs"] = frame_.knobs;
  j["frames"] = m.frames;  // measured and read back: what the means are over
  j["warmup_frames"] = m.warmup_frames;  // before them, until the times settled (common/measure.h)
  j["warmup_seconds"] = m.warmup_seconds;
  j["warmup_settled"] = m.settled;
  j["fragment_counter_bits"] = query_counter_bits(GL_SAMPLES_PASSED);
  auto& passes = j["passes"] = nlohmann::json::array();
  for (const auto& p : m.passes) {
    // fragments: GL_SAMPLES_PASSED over every draw of the pass (a stencil strategy's
    // marking draws too); counts: what the chapter counted itself, e.g. shaded and marking.
    nlohmann::ordered_json pass = {{"name", p.name}, {"mean_ms", p.mean_ms}, {"min_ms", p.min_ms}, {"fragments", p.fragments}};
    if (p.fragments_saturated) pass["fragments_saturated"] = true;
    if (!p.counts.empty()) {
      nlohmann::ordered_json counts = nlohmann::ordered_json::object();
      for (const auto& [what, value] : p.counts) counts[what] = value;
      pass["counts"] = counts;
    }
    pass["frames"] = p.frames;
    passes.push_back(pass);
  }
  j["total_ms"] = m.total_ms();
  j["cpu_ms"] = m.cpu_ms;  // the CPU's time per frame beside the GPU's total (common/measure.h)
  j["render_target_bytes"] = metrics_.allocated_bytes();
  auto& alloc = j["allocations"] = nlohmann::json::array();
  for (const auto& a : metrics_.allocations()) alloc.push_back({{"name", a.name}, {"bytes", a.bytes}});
  std::cout << j.dump() << std::endl;
}

int App::finish() {
  if (options_.update_references) {
    // Record what made the references: a reader's GPU may differ from them by a few steps.
    auto dir = reference_dir();
    std::ofstream(dir / "RENDERER.txt") << context_->renderer() << '\n' << context_->version() << '\n';
    std::cout << chapter_.cli.program << ": updated " << jobs_.size() << " references in " << dir.string()
              << " (" << context_->renderer() << ")\n";
    return 0;
  }
  if (options_.check && exercise_) return finish_exercise_check();
  if (options_.check) {
    if (GLenum e = glGetError(); e != GL_NO_ERROR) std::cerr << "warning: " << gl::error_name(e) << '\n';
    size_t total = jobs_.size();
    std::cout << chapter_.cli.program << ": " << (total - failures_ - missing_) << " of " << total << " references match";
    if (failures_) std::cout << ", " << failures_ << " differ";
    if (missing_) std::cout << ", " << missing_ << " missing";
    std::cout << " (" << context_->renderer() << ")\n";
    if (failures_) return 1;
    if (missing_) return 3;
  }
  return 0;
}

std::filesystem::path App::reference_dir() const {
  auto dir = source_root() / "tests" / "reference" / chapter_.cli.program;
  return exercise_ ? dir / "exercises" : dir;
}

// The verdict on a reader's answer, in words: it matches, or where to look and what was written.
int App::finish_exercise_check() {
  const std::string what = "exercise " + std::to_string(options_.exercise) + " (" + exercise_->title + ")";
  const size_t total = jobs_.size();
  if (missing_) {
    std::cout << what << ": " << missing_ << " of " << total << " expected images are missing (see above)\n";
    return 3;
  }
  if (failures_ == 0) {
    std::cout << what << ": your answer matches the solution in " << (total == 1 ? "the view" : "all " + std::to_string(total) + " views")
              << " (" << context_->renderer() << ")\n";
    return 0;
  }
  std::cout << what << ": your answer does not match the solution in " << failures_ << " of " << total << " views ("
            << context_->renderer() << ").\n  Look at " << exercise_->look_at
            << ".\n  Each 'diff' picture above marks where it differs (its key says how much); 'actual' is yours, "
               "'expected' the solution's.\n  Your file: "
            << exercise_path_ << '\n';
  return 1;
}

bool App::switch_scene() {
  if (scene_request_.empty()) return false;
  const std::string path = std::exchange(scene_request_, {});
  started_ = false;  // the last frame was presented; the next one starts afresh
  try {
    auto scene = std::make_unique<Scene>(load_scene(resolve_input(path)));
    for (const auto& w : scene->warnings) std::cerr << "warning: " << w << '\n';
    // The chapter's objects (which held the old scene's buffers) ended with its body.
    scene_gpu_.reset();
    scene_ = std::move(scene);
    scene_gpu_ = std::make_unique<SceneGpu>(*scene_);
  } catch (const Error& e) {
    scene_error_ = "could not load " + path + ": " + e.what();
    std::cerr << chapter_.cli.program << ": " << scene_error_ << " (kept " << options_.scene << ")\n";
    return true;
  }
  scene_error_.clear();
  options_.scene = path;
  view_ = scene_->cameras.front().name;
  std::cout << "scene: " << path << " (view " << view_ << ")\n";
  fly_to(scene_->camera(view_));
  frame_.index = 0;  // a new shot: state that builds up over frames starts again
  metrics_.clear();
  target_.reset();
  return true;
}

int run_chapter(int argc, const char* const* argv, const Chapter& chapter, const std::function<void(App&)>& body) {
  Options options;
  if (const std::string defect = spec_defect(chapter.cli); !defect.empty()) {
    std::cerr << chapter.cli.program << ": internal error: " << defect << '\n';
    return 1;
  }
  try {
    options = parse_cli(argc, argv, chapter.cli);
  } catch (const UsageError& e) {
    bool help = std::string(e.what()).empty();
    if (!help) std::cerr << chapter.cli.program << ": " << e.what() << "\n\n";
    (help ? std::cout : std::cerr) << usage(chapter.cli);
    if (help && !chapter.exercises.empty()) std::cout << "exercises (--exercise K; with --check: is it right?):\n" << exercise_list(chapter);
    return help ? 0 : 2;
  }
  if (options.exercise > int(chapter.exercises.size())) {
    std::cerr << chapter.cli.program << ": no exercise " << options.exercise << "; "
              << (chapter.exercises.empty() ? "this chapter has none with a check\n" : "its exercises:\n" + exercise_list(chapter));
    return 2;
  }
  try {
    if (options.list) {
      Scene scene = load_scene(resolve_input(options.scene));
      for (const auto& w : scene.warnings) std::cerr << "warning: " << w << '\n';
      std::cout << "views:";
      for (const auto& c : scene.cameras) std::cout << ' ' << c.name;
      std::cout << "\nmodes:";
      for (const auto& m : chapter.cli.modes) std::cout << ' ' << m;
      std::cout << "\nreferences:";
      const std::vector<std::string> scenes = chapter.reference_scenes();
      const auto file = std::filesystem::path(options.scene).filename();
      if (std::any_of(scenes.begin(), scenes.end(), [&](const auto& s) { return std::filesystem::path(s).filename() == file; }))
        for (const auto& s : chapter.references_for(options.scene)) std::cout << ' ' << s.name(chapter.cli);
      else
        std::cout << " (none of this scene)";
      std::cout << "\nreference scenes:";
      for (const auto& s : chapter.reference_scenes()) std::cout << ' ' << s;
      std::cout << "\nknobs:";
      if (chapter.cli.knobs.empty()) std::cout << " none";
      std::cout << '\n' << knob_usage(chapter.cli);
      std::cout << "exercises:" << (chapter.exercises.empty() ? " none\n" : "\n" + exercise_list(chapter));
      return 0;
    }
    if (options.exercise > 0 && chapter.exercises[options.exercise - 1].number) {
      if (options.check || options.update_references) return check_number_exercise(chapter, options);
      // Without --check the program runs as the chapter's own: the number is the reader's to find.
      const Exercise& e = chapter.exercises[options.exercise - 1];
      std::cout << "exercise " << options.exercise << " (" << e.title << ") asks for a number: write it in "
                << exercise_file(chapter, e, false).string() << " ('answer = ...'); --check says whether it is right\n";
      options.exercise = 0;
    }
    // An exercise's shots may be of another scene than the chapter's default: it runs on that one.
    if (options.exercise > 0 && options.scene == chapter.cli.default_scene && !chapter.exercises[options.exercise - 1].scene.empty())
      options.scene = chapter.exercises[options.exercise - 1].scene;
    App app(chapter, options);
    do body(app);  // again after the reader picks another scene in the window's panel
    while (app.switch_scene());
    return app.finish();
  } catch (const UsageError& e) {
    // A chapter's own checks of its options (those only it can make: against the GL's
    // limits, or between knobs) are bad usage too: the message, the usage, exit code 2.
    std::cerr << chapter.cli.program << ": " << e.what() << "\n\n" << usage(chapter.cli);
    return 2;
  } catch (const std::exception& e) {
    std::cerr << chapter.cli.program << ": error: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace lp
