#include "key_bindings.h"

#include "viewer_window.h"

namespace gridrt {

const std::vector<KeyBinding>& keyBindings() {
  static const std::vector<KeyBinding> bindings = {
      {kKeyLeft, "`Left`", ViewAction::OrbitLeft},
      {kKeyRight, "`Right`", ViewAction::OrbitRight},
      {kKeyUp, "`Up`", ViewAction::OrbitUp},
      {kKeyDown, "`Down`", ViewAction::OrbitDown},
      {'=', "`=`", ViewAction::ZoomIn},
      {'-', "`-`", ViewAction::ZoomOut},
      {'w', "`W`", ViewAction::FlyForward},
      {'s', "`S`", ViewAction::FlyBack},
      {'a', "`A`", ViewAction::FlyLeft},
      {'d', "`D`", ViewAction::FlyRight},
      {'e', "`E`", ViewAction::FlyUp},
      {'x', "`X`", ViewAction::FlyDown},
      {'r', "`R`", ViewAction::Reset},
      {kKeyHome, "`Home`", ViewAction::Reset},
      {'c', "`C`", ViewAction::NextCamera},
      {'v', "`V`", ViewAction::NextView},
      {'1', "`1`", ViewAction::ShowImage},
      {'2', "`2`", ViewAction::ShowDepth},
      {'3', "`3`", ViewAction::ShowNormal},
      {'4', "`4`", ViewAction::ShowAlbedo},
      {'5', "`5`", ViewAction::ShowPe},
      {'6', "`6`", ViewAction::ShowTests},
      {'7', "`7`", ViewAction::ShowListLength},
      {'i', "`I`", ViewAction::NextIntersector},
      {'m', "`M`", ViewAction::NextShading},
      {']', "`]`", ViewAction::DeeperRays},
      {'[', "`[`", ViewAction::ShallowerRays},
      {' ', "`Space`", ViewAction::PlayPause},
      {',', "`,`", ViewAction::StepBack},
      {'.', "`.`", ViewAction::StepForward},
      {'p', "`P`", ViewAction::Snapshot},
      {'q', "`Q`", ViewAction::Quit},
      {kKeyEscape, "`Escape`", ViewAction::Quit},
  };
  return bindings;
}

bool actionOfKey(int key, ViewAction& action) {
  for (const KeyBinding& b : keyBindings())
    if (b.key == key) {
      action = b.action;
      return true;
    }
  return false;
}

}  // namespace gridrt
