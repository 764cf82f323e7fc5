// The viewer's keys: what each does, and the words docs/viewer.md lists it under (a test
// checks that the document names every one).
#pragma once
#include <vector>

namespace gridrt {

enum class ViewAction {
  OrbitLeft, OrbitRight, OrbitUp, OrbitDown,
  ZoomIn, ZoomOut,
  FlyForward, FlyBack, FlyLeft, FlyRight, FlyUp, FlyDown,
  Reset, NextCamera,
  NextView, ShowImage, ShowDepth, ShowNormal, ShowAlbedo, ShowPe, ShowTests, ShowListLength,
  NextIntersector, NextShading, DeeperRays, ShallowerRays,
  PlayPause, StepBack, StepForward,
  Snapshot, Quit,
};

struct KeyBinding {
  int key;            // a WindowKey or the key's character (viewer_window.h)
  const char* label;  // the key as docs/viewer.md writes it, e.g. "`W`", "`Left`"
  ViewAction action;
};

const std::vector<KeyBinding>& keyBindings();

// The action of `key`; false when the key does nothing.
bool actionOfKey(int key, ViewAction& action);

}  // namespace gridrt
