#pragma once

#include <string>

namespace glide
{
  /// @p text without white space: values of a scene compared as written
  /// ('0,0' and '0, 0' alike; Scene::unused_entries, the entries a scene
  /// sets twice).
  std::string
  without_white_space(std::string text);
} // namespace glide
