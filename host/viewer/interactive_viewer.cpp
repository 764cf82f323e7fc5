#include "interactive_viewer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "cl_runtime.h"
#include "errors.h"
#include "frame_sequence.h"
#include "image_output.h"
#include "key_bindings.h"
#include "prepared_scene.h"
#include "prepared_triangles.h"
#include "progressive_film.h"
#include "renderer.h"
#include "scene_source.h"
#include "status_line.h"
#include "stopwatch.h"
#include "thread_count.h"
#include "view_camera.h"
#include "view_command.h"
#include "view_pictures.h"
#include "window_module.h"

namespace gridrt {

namespace {

// How long the loop waits for input once the picture is complete (nothing to render).
constexpr int kIdleWaitMs = 50;

// The deepest --max-depth the ] key reaches (the command line's limit).
constexpr int kMaxViewDepth = 64;

// A time within this many frames of a frame's time is at that frame (frame / fps in double
// is off the exact time by an ulp or so): the steps go to the frames of --frames.
constexpr double kFrameSnap = 1e-6;

// The prepared scene (grid and intersector) serves every eye within this many scene
// diagonals of the scene's box; an eye further out builds it again. A farther box only
// grows the grid's margin (the hits stay the same), so orbit, pan and zoom keep it.
constexpr float kEyeReachShare = 1.0f;

// What an input changed, from the least to the most work it makes. Camera: a new eye or
// target, which keeps the prepared scene while the eye stays in the box it was built for
// (InteractiveViewer::moveCamera); Pose: the animation's time (the scene posed again);
// Scene: loaded again (another camera).
enum class Change { None, Picture, Renderer, Camera, Prepared, Pose, Scene };

Change atLeast(Change a, Change b) { return std::max(a, b); }

class InteractiveViewer {
 public:
  explicit InteractiveViewer(const Options& given)
      : start_(given), o_(given) {}

  int run();

 private:
  void loadSceneForView();
  void prepare();
  void moveCamera();
  void makeRenderer();
  // Does the work `change` calls for (the scene posed again, the grid and intersector
  // built, the renderer made), then change is None.
  void update(Change& change);
  void renderSample();
  void show();
  Change apply(const WindowEvent& e, bool& quit);
  Change act(ViewAction action, bool& quit);
  // The current camera's look-at (the command line's --look-at, or one made from the
  // scene's camera).
  LookAt lookAt() const;
  Camera currentCamera() const { return chooseCamera(o_, scene_, framing_); }
  Change moveTo(const LookAt& view);
  Change setTime(double t);
  void snapshot();
  int targetSamples() const { return o_.adaptive_aa ? 1 : std::max(1, o_.spp); }
  float sceneDiagonal() const {
    const Bounds b = sceneBounds(scene_);
    return b.empty() ? 1.0f : glm::length(b.hi - b.lo);
  }

  const Options start_;  // as the command line gave them: R goes back to them
  Options o_;            // the options of the view shown
  ViewKind view_ = ViewKind::Image;
  std::unique_ptr<ClRuntime> runtime_;  // opened once the window is
  SceneSource source_;
  Scene scene_;
  Bounds framing_;
  Camera camera_;
  std::unique_ptr<PreparedScene> prepared_;
  Bounds prepared_reach_;  // where the eye may go with prepared_ kept (kEyeReachShare)
  bool prepared_for_camera_ = false;  // prepared_'s grid is the camera's own (the command line's)
  std::unique_ptr<Renderer> renderer_;
  std::unique_ptr<ViewerWindow> window_;
  Frame frame_;
  PrimaryAovs aovs_;  // sample 0's, as the command line's AOVs
  ProgressiveFilm film_;
  FrameStatus status_;
  std::vector<SceneImage> images_;  // the scene's images, decoded once for every pose
  bool warned_ = false;             // the scene's warnings are said once
  bool playing_ = false;
  std::string note_;  // said in the title until the view changes
};

void InteractiveViewer::loadSceneForView() {
  source_ = loadScene(o_, o_.time, scene_);
  images_ = scene_.images;
  if (!o_.quiet && !warned_) {
    warned_ = true;
    for (const auto& w : source_.warnings) std::cerr << "gridrt: warning: " << w << '\n';
    for (const auto& w : scene_.warnings) std::cerr << "gridrt: warning: " << w << '\n';
  }
  framing_ = scene_.has_camera ? Bounds{} : sceneBounds(source_.animated ? source_.animated->still()
                                                                         : scene_);
}

void InteractiveViewer::prepare() {
  camera_ = chooseCamera(o_, scene_, framing_);
  renderer_.reset();
  prepared_.reset();
  // Built for rays from anywhere near the scene, so that moving the eye keeps it; for the
  // views of the structure (PE, tests, list length) the grid the command line would build
  // for this camera, whose margin, hence cells, depend on the eye.
  prepared_reach_ = primaryRayOrigins(camera_, o_.width, o_.height);
  prepared_for_camera_ = needsDiagnostics(view_);
  const Bounds box = sceneBounds(scene_);
  if (!box.empty() && !prepared_for_camera_) {
    const glm::vec3 reach = kEyeReachShare * glm::vec3(glm::length(box.extent()));
    prepared_reach_.grow(box.lo - reach);
    prepared_reach_.grow(box.hi + reach);
  }
  prepared_ = std::make_unique<PreparedScene>(o_, *runtime_, scene_, prepared_reach_);
  makeRenderer();
}

void InteractiveViewer::moveCamera() {
  camera_ = chooseCamera(o_, scene_, framing_);
  const Bounds origins = primaryRayOrigins(camera_, o_.width, o_.height);
  const bool inside = !origins.empty() && glm::all(glm::greaterThanEqual(origins.lo, prepared_reach_.lo)) &&
                      glm::all(glm::lessThanEqual(origins.hi, prepared_reach_.hi));
  if (!prepared_ || !inside || prepared_for_camera_) {
    prepare();
    return;
  }
  renderer_.reset();
  makeRenderer();
}

void InteractiveViewer::makeRenderer() {
  RenderSettings settings = renderSettings(o_);
  settings.want_aovs = needsAovs(view_);
  settings.want_diagnostics = needsDiagnostics(view_);
  renderer_ = std::make_unique<Renderer>(scene_, camera_, prepared_->intersector(), settings);
}

void InteractiveViewer::renderSample() {
  Stopwatch clock;
  const int k = film_.samples();
  renderer_->setSingleSample(targetSamples() > 1 ? k : -1);
  const IntersectCounters before = prepared_->intersector().counters();
  renderer_->render(frame_);
  const IntersectCounters& after = prepared_->intersector().counters();
  film_.add(frame_.film);
  if (k == 0) aovs_ = frame_.aovs;
  status_.lists_ms = after.listsMs() - before.listsMs();
  status_.kernel_ms = after.kernel_ms - before.kernel_ms;
  status_.phase2_ms = after.reduce_ms - before.reduce_ms;
  status_.shading_ms = frame_.times.shade_ms;
  status_.frame_ms = frame_.times.frame_ms;
  status_.rays = frame_.rays.total();
  status_.wall_ms = clock.ms();
}

void InteractiveViewer::show() {
  const Picture p = view_ == ViewKind::Image ? imagePicture(film_.mean())
                                             : aovPicture(view_, aovs_, frame_.film.width,
                                                          frame_.film.height);
  window_->present(p.rgb.data(), p.width, p.height);
  status_.view = viewName(view_);
  status_.samples = film_.samples();
  status_.target_samples = targetSamples();
  status_.time = o_.time;
  status_.playing = playing_;
  status_.note = note_;
  window_->setTitle(statusLine(status_));
}

LookAt InteractiveViewer::lookAt() const {
  if (o_.eye) return LookAt{*o_.eye, *o_.target};
  return lookAtOf(currentCamera(), sceneBounds(scene_));
}

Change InteractiveViewer::moveTo(const LookAt& view) {
  if (!(glm::length(view.target - view.eye) > 0.0f) || !std::isfinite(view.eye.x + view.eye.y +
                                                                      view.eye.z))
    return Change::None;  // a move that would put the eye on the target is not taken
  o_.eye = view.eye;
  o_.target = view.target;
  return Change::Camera;
}

Change InteractiveViewer::setTime(double t) {
  const bool posed = o_.time.has_value();
  o_.time = std::max(0.0, t);
  // The first time loads the animations (a still scene is loaded without them).
  return posed ? Change::Pose : Change::Scene;
}

Change InteractiveViewer::act(ViewAction action, bool& quit) {
  const float step = kFlyShareOfScene * sceneDiagonal();
  switch (action) {
    case ViewAction::OrbitLeft: return moveTo(orbited(lookAt(), -kOrbitDegreesPerKey, 0.0f));
    case ViewAction::OrbitRight: return moveTo(orbited(lookAt(), kOrbitDegreesPerKey, 0.0f));
    case ViewAction::OrbitUp: return moveTo(orbited(lookAt(), 0.0f, kOrbitDegreesPerKey));
    case ViewAction::OrbitDown: return moveTo(orbited(lookAt(), 0.0f, -kOrbitDegreesPerKey));
    case ViewAction::ZoomIn: return moveTo(zoomed(lookAt(), 1));
    case ViewAction::ZoomOut: return moveTo(zoomed(lookAt(), -1));
    case ViewAction::FlyForward: return moveTo(flown(lookAt(), {0, 0, 1}, step));
    case ViewAction::FlyBack: return moveTo(flown(lookAt(), {0, 0, -1}, step));
    case ViewAction::FlyLeft: return moveTo(flown(lookAt(), {-1, 0, 0}, step));
    case ViewAction::FlyRight: return moveTo(flown(lookAt(), {1, 0, 0}, step));
    case ViewAction::FlyUp: return moveTo(flown(lookAt(), {0, 1, 0}, step));
    case ViewAction::FlyDown: return moveTo(flown(lookAt(), {0, -1, 0}, step));
    case ViewAction::Reset: {
      const int width = o_.width, height = o_.height;
      o_ = start_;
      o_.width = width, o_.height = height, o_.size_given = true;
      playing_ = false;
      return Change::Scene;
    }
    case ViewAction::NextCamera: {
      // The next glTF camera in traversal order, after the last the first.
      const std::string previous = o_.camera_name;
      int index = 0;
      try {
        index = previous.empty() ? 1 : std::stoi(previous) + 1;
      } catch (const std::exception&) {
        index = 0;  // a camera named on the command line: start from the first
      }
      o_.eye.reset(), o_.target.reset(), o_.fov_degrees.reset();
      for (int attempt : {index, 0}) {
        o_.camera_name = std::to_string(attempt);
        try {
          loadSceneForView();
          note_ = "camera " + o_.camera_name;
          return Change::Prepared;
        } catch (const std::exception&) {
        }
      }
      o_.camera_name = previous;  // the scene as it was (a failed load changes nothing)
      note_ = "no other camera";
      return Change::Picture;
    }
    case ViewAction::NextView:
      view_ = nextView(view_);
      return Change::Renderer;
    case ViewAction::ShowImage: view_ = ViewKind::Image; return Change::Renderer;
    case ViewAction::ShowDepth: view_ = ViewKind::Depth; return Change::Renderer;
    case ViewAction::ShowNormal: view_ = ViewKind::Normal; return Change::Renderer;
    case ViewAction::ShowAlbedo: view_ = ViewKind::Albedo; return Change::Renderer;
    case ViewAction::ShowPe: view_ = ViewKind::Pe; return Change::Renderer;
    case ViewAction::ShowTests: view_ = ViewKind::Tests; return Change::Renderer;
    case ViewAction::ShowListLength: view_ = ViewKind::ListLength; return Change::Renderer;
    case ViewAction::NextIntersector:
      o_.accel = o_.accel == AccelKind::GridRt ? AccelKind::Dda
                 : o_.accel == AccelKind::Dda  ? AccelKind::Brute
                                               : AccelKind::GridRt;
      return Change::Prepared;
    case ViewAction::NextShading:
      o_.shading = o_.shading == ShadingModel::Phong ? ShadingModel::Gltf : ShadingModel::Phong;
      return Change::Renderer;
    case ViewAction::DeeperRays:
      o_.max_depth = std::min(o_.max_depth + 1, kMaxViewDepth);
      return Change::Renderer;
    case ViewAction::ShallowerRays:
      o_.max_depth = std::max(o_.max_depth - 1, 0);
      return Change::Renderer;
    case ViewAction::PlayPause:
      playing_ = !playing_;
      return o_.time ? Change::Picture : setTime(0.0);
    case ViewAction::StepBack:
    case ViewAction::StepForward: {
      // To the frame before or after the time shown, as --frames numbers them.
      playing_ = false;
      const double frame = o_.time.value_or(0.0) * o_.fps;
      const long to = action == ViewAction::StepForward ? long(std::floor(frame + kFrameSnap)) + 1
                                                        : long(std::ceil(frame - kFrameSnap)) - 1;
      return setTime(frameTime(std::max(0L, to), o_.fps));
    }
    case ViewAction::Snapshot:  // taken by the loop, once the view is up to date
      return Change::None;
    case ViewAction::Quit:
      quit = true;
      return Change::None;
  }
  return Change::None;
}

Change InteractiveViewer::apply(const WindowEvent& e, bool& quit) {
  switch (e.kind) {
    case WindowEvent::Kind::Quit:
      quit = true;
      return Change::None;
    case WindowEvent::Kind::Key: {
      ViewAction action;
      return actionOfKey(e.key, action) ? act(action, quit) : Change::None;
    }
    case WindowEvent::Kind::Drag:
      if (e.button == 1)
        return moveTo(orbited(lookAt(), -kOrbitDegreesPerPixel * float(e.dx),
                              kOrbitDegreesPerPixel * float(e.dy)));
      return moveTo(panned(lookAt(), float(e.dx), float(e.dy), currentCamera().yfov, o_.height));
    case WindowEvent::Kind::Wheel:
      return moveTo(zoomed(lookAt(), e.dy));
    case WindowEvent::Kind::Resized:
      if (e.width < 1 || e.height < 1 || (e.width == o_.width && e.height == o_.height))
        return Change::None;
      o_.width = e.width, o_.height = e.height;
      return Change::Prepared;
  }
  return Change::None;
}

void InteractiveViewer::snapshot() {
  // The command line's own render of these options: a fresh grid and intersector for the
  // camera, one frame of every --spp sample, the file through the same writer.
  const std::string path = snapshotPath(o_);
  const Camera camera = currentCamera();
  PreparedScene prepared(o_, *runtime_, scene_, camera);
  Renderer renderer(scene_, camera, prepared.intersector(), renderSettings(o_));
  Frame frame;
  renderer.render(frame);
  writeLayeredImage(path, filmImage(frame.film), OutputKind::Image, std::nullopt);
  std::cout << commandLineOf(o_) << std::endl;
  if (!o_.quiet) std::cerr << "gridrt: wrote " << path << '\n';
  note_ = "wrote " + path;
}

int InteractiveViewer::run() {
  loadSceneForView();
  o_ = sizedForCamera(o_, chooseCamera(o_, scene_, framing_));
  o_.size_given = true;  // the window's size from here on
  window_ = openViewerWindow(statusLine(status_), o_.width, o_.height);
  runtime_ = std::make_unique<ClRuntime>(o_.device);
  if (!o_.quiet)
    std::cerr << "gridrt: device " << runtime_->info().platform_index << ":"
              << runtime_->info().device_index << " " << runtime_->info().name << '\n';
  status_.scene = o_.scene.empty() ? "default scene" : o_.scene;
  status_.device = runtime_->info().name;
  Change change = Change::Prepared;
  Stopwatch animation_clock;
  bool quit = false;
  while (!quit) {
    const bool busy = change != Change::None || playing_ || film_.samples() < targetSamples();
    for (const WindowEvent& e : window_->events(busy ? 0 : kIdleWaitMs)) {
      ViewAction action;
      if (e.kind == WindowEvent::Kind::Key && actionOfKey(e.key, action) &&
          action == ViewAction::Snapshot) {
        update(change);  // the keys before P are in the snapshot, those after it are not
        snapshot();
        change = Change::Picture;  // the note in the title
        continue;
      }
      change = atLeast(change, apply(e, quit));
      if (quit) return 0;
    }
    if (playing_ && change < Change::Pose) {
      const double dt = animation_clock.ms() / 1000.0;
      change = atLeast(change, setTime(o_.time.value_or(0.0) + dt));
    }
    animation_clock.restart();
    const bool show_anyway = change == Change::Picture;
    update(change);
    if (film_.samples() < targetSamples()) {
      renderSample();
      show();
    } else if (show_anyway) {
      show();
    }
  }
  return 0;
}

void InteractiveViewer::update(Change& change) {
  Stopwatch clock;
  if (change == Change::Scene || (change == Change::Pose && !source_.animated)) {
    loadSceneForView();
  } else if (change == Change::Pose) {
    scene_ = source_.animated->at(*o_.time);
    scene_.images = images_;  // decoded once, as the command line's frames share them
  }
  if (change >= Change::Prepared) {
    prepare();
    status_.triangles = scene_.triangleCount();
    status_.pes = prepared_->grid() ? prepared_->grid()->peCount() : 0;
    status_.accel = prepared_->intersector().name();
  } else if (change == Change::Camera) {
    moveCamera();
  } else if (change == Change::Renderer) {
    if (needsDiagnostics(view_) && !prepared_for_camera_)
      prepare();  // a view of the structure: the camera's own grid
    else
      makeRenderer();
  }
  if (change >= Change::Renderer) {
    film_.restart();
    note_.clear();
    if (playing_ && source_.animated && !source_.animated->moves()) {
      playing_ = false;
      note_ = "nothing moves";
    }
    status_.setup_ms = clock.ms();
  } else if (film_.samples() > 0) {
    status_.setup_ms = 0;  // a further sample of the same view
  }
  change = Change::None;
}

}  // namespace

int runViewer(const Options& options) {
  try {
    // Without a display nothing else is worth doing: said before the scene is loaded.
    checkDisplay();
    const ThreadLimit thread_limit(options.threads);
    InteractiveViewer viewer(options);
    return viewer.run();
  } catch (const NoDisplay& e) {
    std::cerr << "gridrt: no display: " << e.what() << '\n';
    return 1;
  }
}

}  // namespace gridrt
