// Scene-file names of the world's settings enums.
#include <collide/body.h>
#include <collide/error.h>
#include <collide/settings.h>

#include <array>
#include <string>

namespace collide {

namespace {

template <class Enum, std::size_t N>
Enum parseName(std::string_view name, const std::array<std::string_view, N>& names, const char* what) {
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i] == name) return static_cast<Enum>(i);
  }
  std::string expected;
  for (std::size_t i = 0; i < N; ++i) expected += (i ? ", " : "") + std::string(names[i]);
  throw Error(std::string(what) + ": unknown name \"" + std::string(name) + "\", expected one of " +
              expected);
}

constexpr std::array<std::string_view, 4> kCombineNames{"average", "min", "max", "multiply"};
constexpr std::array<std::string_view, 2> kImpactNames{"newton", "interpolated"};
constexpr std::array<std::string_view, 4> kFrictionNames{"coulomb", "viscous", "damping", "none"};
constexpr std::array<std::string_view, 2> kPenetrationNames{"project", "revert"};
constexpr std::array<std::string_view, 3> kBodyTypeNames{"static", "kinematic", "dynamic"};

}  // namespace

std::string_view toString(CombineRule rule) { return kCombineNames[static_cast<int>(rule)]; }
std::string_view toString(ImpactModel model) { return kImpactNames[static_cast<int>(model)]; }
std::string_view toString(FrictionModel model) { return kFrictionNames[static_cast<int>(model)]; }
std::string_view toString(PenetrationResponse response) {
  return kPenetrationNames[static_cast<int>(response)];
}
std::string_view toString(BodyType type) { return kBodyTypeNames[static_cast<int>(type)]; }

CombineRule parseCombineRule(std::string_view name) {
  return parseName<CombineRule>(name, kCombineNames, "combine rule");
}
ImpactModel parseImpactModel(std::string_view name) {
  return parseName<ImpactModel>(name, kImpactNames, "impact model");
}
FrictionModel parseFrictionModel(std::string_view name) {
  return parseName<FrictionModel>(name, kFrictionNames, "friction model");
}
PenetrationResponse parsePenetrationResponse(std::string_view name) {
  return parseName<PenetrationResponse>(name, kPenetrationNames, "penetration response");
}

}  // namespace collide
