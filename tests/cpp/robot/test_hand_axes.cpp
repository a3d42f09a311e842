// A hand's grasp axes (Hand::approach_axis, Hand::fingertips) against hands whose answer is known by construction:
// a linkage gripper along +x (knuckle and pad per finger), a hand tilted off every axis, and the <graspmix> element.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "graspmix/robot/hand.hpp"

using graspmix::Hand;

namespace {

// A palm and two fingers along the wrist's +x at y = +-d, mirror images: each an outer knuckle (revolute about z)
// carrying a pad that reaches to x = 0.16, and an inner knuckle (a leaf, mimicking the drive) reaching x = 0.09.
std::string linkage(const std::string& extra = "") {
  std::string out =
      R"(<robot name="linkage"><link name="palm"><collision><geometry><box size="0.04 0.08 0.04"/></geometry></collision></link>)";
  for (const std::string side : {"l", "r"}) {
    const std::string y = side == "l" ? "0.03" : "-0.03";
    const std::string mimic = side == "l" ? "" : R"(<mimic joint="drive"/>)";
    const std::string drive = side == "l" ? "drive" : "r_drive";
    out += "<link name='" + side +
           "_outer'><collision><origin xyz='0.03 0 0'/><geometry><box size='0.06 0.01 "
           "0.01'/></geometry></collision></link>";
    out +=
        "<link name='" + side +
        "_pad'><collision><origin xyz='0.05 0 0'/><geometry><box size='0.02 0.01 0.02'/></geometry></collision></link>";
    out += "<link name='" + side +
           "_inner'><collision><origin xyz='0.035 0 0'/><geometry><box size='0.05 0.01 "
           "0.01'/></geometry></collision></link>";
    out += "<joint name='" + drive + "' type='revolute'><parent link='palm'/><child link='" + side +
           "_outer'/><origin xyz='0.02 " + y +
           " 0'/><axis xyz='0 0 1'/><limit lower='0' upper='0.2' effort='1' velocity='1'/>" + mimic + "</joint>";
    out += "<joint name='" + side + "_pad_joint' type='fixed'><parent link='" + side + "_outer'/><child link='" + side +
           "_pad'/><origin xyz='0.06 0 0'/></joint>";
    out +=
        "<joint name='" + side + "_inner_joint' type='revolute'><parent link='palm'/><child link='" + side +
        "_inner'/><origin xyz='0.02 " + y +
        " 0'/><axis xyz='0 0 1'/><limit lower='0' upper='0.2' effort='1' velocity='1'/><mimic joint='drive'/></joint>";
  }
  return out + extra + "</robot>";
}

std::vector<std::string> tips(const Hand& h) {
  std::vector<std::string> out;
  for (const int l : h.fingertips()) out.push_back(h.link_names()[static_cast<size_t>(l)]);
  return out;
}

}  // namespace

TEST(HandAxes, LinkageFingertipsAreThePadsAndTheApproachSnapsToX) {
  const Hand h = Hand::from_urdf_string(linkage(), ".");
  EXPECT_EQ(tips(h), (std::vector<std::string>{"l_pad", "r_pad"}));
  EXPECT_EQ(h.approach_axis(), Eigen::Vector3d::UnitX());  // exactly: snapped
  EXPECT_EQ(h.grasp_axes_source(), "inferred");
}

TEST(HandAxes, ATiltedHandKeepsTheExactDirection) {
  // The fingertip sphere at (0.1, 0, 0.1) from the wrist: 45 degrees from x and z, no axis within 20 degrees.
  const Hand h =
      Hand::from_urdf_string(R"(<robot name="tilt"><link name="w"/><link name="f"><collision><origin xyz="0.1 0 0.1"/>
    <geometry><sphere radius="0.01"/></geometry></collision></link><joint name="j" type="prismatic"><parent link="w"/>
    <child link="f"/><axis xyz="0 1 0"/><limit lower="0" upper="0.01" effort="1" velocity="1"/></joint></robot>)",
                             ".");
  // The mid-range joint moves the sphere 5 mm along y; the box of its tessellation is centred on its centre.
  const Eigen::Vector3d expected = Eigen::Vector3d(0.1, 0.005, 0.1).normalized();
  EXPECT_LT((h.approach_axis() - expected).norm(), 1e-9);
  graspmix::HandLoadSettings wide;
  wide.approach_snap_deg = 46.0;
  const Hand snapped =
      Hand::from_urdf_string(R"(<robot name="tilt"><link name="w"/><link name="f"><collision><origin xyz="0.1 0 0.1"/>
    <geometry><sphere radius="0.01"/></geometry></collision></link><joint name="j" type="prismatic"><parent link="w"/>
    <child link="f"/><axis xyz="0 1 0"/><limit lower="0" upper="0.01" effort="1" velocity="1"/></joint></robot>)",
                             ".", wide);
  EXPECT_TRUE(snapped.approach_axis() == Eigen::Vector3d::UnitX() ||
              snapped.approach_axis() == Eigen::Vector3d::UnitZ());
}

TEST(HandAxes, TheUrdfElementGivesThemAndTheRestIsInferred) {
  const Hand both =
      Hand::from_urdf_string(linkage(R"(<graspmix approach_axis="0 0 2" fingertips="l_inner r_inner"/>)"), ".");
  EXPECT_EQ(both.approach_axis(), Eigen::Vector3d::UnitZ());
  EXPECT_EQ(tips(both), (std::vector<std::string>{"l_inner", "r_inner"}));
  EXPECT_EQ(both.grasp_axes_source(), "urdf");
  // Fingertips alone: the approach from them (the inner knuckles' boxes also lie along +x).
  const Hand tips_only = Hand::from_urdf_string(linkage(R"(<graspmix fingertips="l_inner r_inner"/>)"), ".");
  EXPECT_EQ(tips_only.approach_axis(), Eigen::Vector3d::UnitX());
}

TEST(HandAxes, BadAxesAreErrorsNamingThem) {
  const auto fails = [](const std::string& element, const std::string& part) {
    try {
      (void)Hand::from_urdf_string(linkage(element), ".");
      ADD_FAILURE() << element;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  fails(R"(<graspmix approach_axis="1 0 nan"/>)", "approach_axis must be three finite numbers");
  fails(R"(<graspmix fingertips="palm"/>)", "'palm' is not moved by any joint");
  fails(R"(<graspmix fingertips="nope"/>)", "'nope' is not a link");
  fails(R"(<graspmix fingertips=""/>)", "names no link");
  Hand h = Hand::from_urdf_string(linkage(), ".");
  EXPECT_THROW(h.set_grasp_axes(Eigen::Vector3d::Zero(), {"l_pad"}), std::invalid_argument);
  EXPECT_THROW(h.set_grasp_axes(Eigen::Vector3d::UnitZ(), {}), std::invalid_argument);
  h.set_grasp_axes(Eigen::Vector3d(0, 0, 3), {"r_pad"});
  EXPECT_EQ(h.approach_axis(), Eigen::Vector3d::UnitZ());
  EXPECT_EQ(tips(h), std::vector<std::string>{"r_pad"});
}

TEST(HandAxes, ThreeFingersAroundTheApproachAreThreeFingertips) {
  // Three fingers 120 degrees apart about z, each a proximal box and a distal box beyond it: the distal ones.
  std::string urdf =
      R"(<robot name="three"><link name="palm"><collision><geometry><box size="0.1 0.1 0.02"/></geometry></collision></link>)";
  for (int k = 0; k < 3; ++k) {
    const double a = 2.0 * M_PI * k / 3.0;
    const std::string f = "f" + std::to_string(k), c = std::to_string(0.04 * std::cos(a)),
                      s = std::to_string(0.04 * std::sin(a));
    const std::string axis = std::to_string(-std::cos(a)) + " " + std::to_string(-std::sin(a)) + " 0";
    urdf += "<link name='" + f +
            "_proximal'><collision><origin xyz='0 0 0.03'/><geometry><box size='0.01 0.01 "
            "0.04'/></geometry></collision></link>";
    urdf += "<link name='" + f +
            "_distal'><collision><origin xyz='0 0 0.02'/><geometry><box size='0.01 0.01 "
            "0.03'/></geometry></collision></link>";
    urdf += "<joint name='" + f + "_slide' type='prismatic'><parent link='palm'/><child link='" + f +
            "_proximal'/><origin xyz='" + c + " " + s + " 0.01'/><axis xyz='" + axis +
            "'/><limit lower='0' upper='0.03' effort='1' velocity='1'/></joint>";
    urdf += "<joint name='" + f + "_bend' type='revolute'><parent link='" + f + "_proximal'/><child link='" + f +
            "_distal'/><origin xyz='0 0 0.05'/><axis xyz='0 1 0'/><limit lower='-0.1' upper='0.1' effort='1' "
            "velocity='1'/></joint>";
  }
  const Hand h = Hand::from_urdf_string(urdf + "</robot>", ".");
  EXPECT_EQ(tips(h), (std::vector<std::string>{"f0_distal", "f1_distal", "f2_distal"}));
  EXPECT_EQ(h.approach_axis(), Eigen::Vector3d::UnitZ());
}
