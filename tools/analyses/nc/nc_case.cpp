#include "nc_case.h"

#include <cmath>
#include <cstdio>

#include "mechsim/catalog/coupling/coupling_spec.h"
#include "mechsim/catalog/nc_params.h"

namespace mechsim::tools::nc_analyses {

namespace nc = models::nc;

namespace {

// The slide drive data keys of a slide's params (the rest of its keys drive the time run).
const std::vector<std::string> slide_data_keys{"slide_mass",    "spindle_diameter", "lead",
                                               "spindle_length", "density",          "shear_modulus",
                                               "coupling_inertia", "coupling_stiffness", "slide_inertia"};

std::vector<const config::ParticipantSpec*> participants_of_type(const config::Scene& scene, const std::string& type) {
  std::vector<const config::ParticipantSpec*> found;
  for (const auto& p : scene.participants)
    if (p.type == type) found.push_back(&p);
  return found;
}

std::string first_of_many_note(const std::vector<const config::ParticipantSpec*>& found, const std::string& type) {
  return std::to_string(found.size()) + " " + type + " participants: the first ('" + found.front()->name +
         "') is analysed";
}

std::string format_stiffness(double c) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g N m/rad", c);
  return text;
}

}  // namespace

MotorCase motor_case_from_scene(const config::Scene& scene, const NcDesignSettings& settings) {
  MotorCase result;
  const auto tachometers = participants_of_type(scene, "tachometer");
  if (!tachometers.empty()) {
    const config::ParticipantSpec& p = *tachometers.front();
    if (settings.motor)
      settings.motor->fail("expected no motor data here: the scene's tachometer participant '" + p.name +
                           "' supplies it");
    result.params = cosim::parse_motor_tacho_params(p.params);
    result.source = {"participant", p.key_path + ".params"};
    if (tachometers.size() > 1) result.notes.push_back(first_of_many_note(tachometers, "tachometer"));
  } else if (settings.motor) {
    result.params = cosim::parse_motor_tacho_params(*settings.motor);
    result.source = {"design", settings.motor->path()};
  } else {
    result.source = {"defaults", ""};
    result.notes.push_back("no tachometer participant and no design.motor: the spec's identified motor-tacho set");
  }
  return result;
}

SlideCase slide_case_from_scene(const config::Scene& scene, const NcDesignSettings& settings) {
  SlideCase result;
  const auto slides = participants_of_type(scene, "slide");
  if (slides.empty()) {
    if (settings.slide) {
      settings.slide->allow_only(slide_data_keys);
      result.data = cosim::parse_slide_drive_data(*settings.slide);
      result.source = {"design", settings.slide->path()};
      result.coupling_stiffness_source = {settings.slide->has("coupling_stiffness") ? "design" : "defaults",
                                          settings.slide->path()};
    } else {
      result.source = {"defaults", ""};
      result.coupling_stiffness_source = {"defaults", ""};
      result.notes.push_back("no slide participant and no design.slide: the CNC 200 defaults, I_slide = m s^2/4 pi^2");
    }
    return result;
  }

  const config::ParticipantSpec& p = *slides.front();
  if (settings.slide)
    settings.slide->fail("expected no slide data here: the scene's slide participant '" + p.name + "' supplies it");
  // All of the slide's keys are validated, as the node type would; only the drive data is used.
  result.data = cosim::parse_slide_options(p.params).drive;
  result.source = {"participant", p.key_path + ".params"};
  result.coupling_stiffness_source = {p.params.has("coupling_stiffness") ? "participant" : "defaults",
                                      p.key_path + ".params"};
  if (slides.size() > 1) result.notes.push_back(first_of_many_note(slides, "slide"));

  // In a time run the coupling spring belongs to the connection: use it, and refuse a
  // different value in the slide's params, which the time run would silently ignore.
  for (const auto& c : scene.connections) {
    if (!c.coupling || (c.from != p.name && c.to != p.name)) continue;
    const double stiffness = cosim::coupling::parse_coupling(*c.coupling).params.stiffness;
    if (p.params.has("coupling_stiffness") &&
        std::abs(result.data.coupling_stiffness - stiffness) > 1e-9 * stiffness)
      p.params.child("coupling_stiffness")
          .fail("expected the stiffness of the coupling element of " + c.key_path + " (" + format_stiffness(stiffness) +
                ") or no value: the time run uses the connection's");
    result.data.coupling_stiffness = stiffness;
    result.coupling_stiffness_source = {"connection", c.key_path + ".coupling"};
    break;
  }
  return result;
}

}  // namespace mechsim::tools::nc_analyses
