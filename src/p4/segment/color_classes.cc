#include "p4/segment/color_classes.h"

#include <algorithm>

namespace p4::segment {

bool ColorClass::IsValid(std::string* error) const {
  if (y[0] > y[1] || u[0] > u[1] || v[0] > v[1]) {
    if (error) *error = "class '" + name + "': a lower bound is above its upper bound";
    return false;
  }
  if (name.empty()) {
    if (error) *error = "a class has no name";
    return false;
  }
  return true;
}

bool ColorClassSet::IsValid(std::string* error) const {
  if (classes.empty()) {
    if (error) *error = "no colour class";
    return false;
  }
  if (classes.size() > 32) {
    if (error) *error = "more than 32 colour classes (" + std::to_string(classes.size()) + ")";
    return false;
  }
  for (const auto& c : classes) {
    if (!c.IsValid(error)) return false;
  }
  return true;
}

ColorLut ColorClassSet::BuildLut() const {
  ColorLut lut;
  for (std::size_t k = 0; k < classes.size() && k < 32; ++k) {
    const uint32_t bit = 1u << k;
    const ColorClass& c = classes[k];
    for (int i = c.y[0]; i <= c.y[1]; ++i) lut.y[i] |= bit;
    for (int i = c.u[0]; i <= c.u[1]; ++i) lut.u[i] |= bit;
    for (int i = c.v[0]; i <= c.v[1]; ++i) lut.v[i] |= bit;
  }
  return lut;
}

uint32_t ColorClassSet::MaskOf(const std::string& prefix) const {
  uint32_t mask = 0;
  for (std::size_t k = 0; k < classes.size() && k < 32; ++k) {
    if (classes[k].name.rfind(prefix, 0) == 0) mask |= 1u << k;
  }
  return mask;
}

ColorClassSet DefaultOrangeBall() {
  // Orange (R 1.0, G 0.42, B 0.05) lit from 60 % to 110 % lands at Y 90-155, U 60-90,
  // V 170-205; a red-brown floor sits near V 150 and skin near V 140-155, below every box.
  ColorClassSet set;
  set.classes.push_back({"ball_bright", {125, 240}, {50, 100}, {180, 240}});
  set.classes.push_back({"ball_mid", {95, 170}, {55, 108}, {170, 230}});
  set.classes.push_back({"ball_dark", {60, 125}, {70, 112}, {162, 215}});
  return set;
}

ColorClassSet DefaultYellowBall() {
  // Yellow (R 0.97, G 0.86, B 0.18) lit from 50 % to 115 % lands at Y 100-225, U 35-90,
  // V 138-160 (greener or redder yellows and white balance widen it).
  ColorClassSet set;
  set.classes.push_back({"ball_bright", {150, 245}, {25, 95}, {132, 175}});
  set.classes.push_back({"ball_dark", {80, 160}, {50, 105}, {132, 165}});
  return set;
}

ColorClassSet NamedBall(const std::string& name) {
  return name == "white"    ? DefaultWhiteBall()
         : name == "yellow" ? DefaultYellowBall()
                            : DefaultOrangeBall();
}
ColorClassSet DefaultWhiteBall() {
  ColorClassSet set;
  set.classes.push_back({"ball_white", {185, 255}, {112, 144}, {112, 144}});
  set.classes.push_back({"ball_grey", {150, 200}, {116, 140}, {116, 140}});
  return set;
}

std::vector<ColorClass> LearnClasses(std::span<const YuvSample> samples, const std::string& name,
                                     int boxes, int margin) {
  std::vector<YuvSample> sorted(samples.begin(), samples.end());
  std::sort(sorted.begin(), sorted.end(),
            [](const YuvSample& a, const YuvSample& b) { return a.y < b.y; });
  boxes = std::max(1, std::min<int>(boxes, static_cast<int>(sorted.size())));
  std::vector<ColorClass> out;
  for (int b = 0; b < boxes; ++b) {
    const std::size_t lo = sorted.size() * b / boxes, hi = sorted.size() * (b + 1) / boxes;
    std::vector<uint8_t> ys, us, vs;
    for (std::size_t i = lo; i < hi; ++i) {
      ys.push_back(sorted[i].y), us.push_back(sorted[i].u), vs.push_back(sorted[i].v);
    }
    const auto range = [&](std::vector<uint8_t>& x) {
      std::sort(x.begin(), x.end());
      const int a = x[x.size() * 2 / 100], z = x[std::min(x.size() - 1, x.size() * 98 / 100)];
      return std::array<uint8_t, 2>{static_cast<uint8_t>(std::max(0, a - margin)),
                                    static_cast<uint8_t>(std::min(255, z + margin))};
    };
    ColorClass c;
    c.name = name + "_" + std::to_string(b);
    c.y = range(ys);
    c.u = range(us);
    c.v = range(vs);
    out.push_back(c);
  }
  return out;
}

}  // namespace p4::segment
