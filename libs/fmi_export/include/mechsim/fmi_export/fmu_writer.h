// `mechsim fmu export`: a co-simulation FMU of one participant of a scene (docs/fmi.md,
// "Exporting mechsim models as FMUs"). The archive holds
//   modelDescription.xml                       written here from the participant's variables
//   binaries/<platform>/<id>.so                the prebuilt mechsim_fmu binary (one for all
//                                              participants), named after the model identifier
//   binaries/<platform>/libyaml-cpp.so.0.7     beside it (its RUNPATH is $ORIGIN)
//   resources/participant.yaml                 what the binary plays (ExportConfig)
// The binaries are stored uncompressed: an importer unpacks them at every instantiation.
#pragma once

#include <string>
#include <vector>

#include "mechsim/config/scene.h"
#include "mechsim/fmi_export/exported_participant.h"

namespace mechsim::fmi_export {

struct ExportRequest {
  std::string type;         // the node type the user names; must be the participant's
  std::string participant;  // instance name in the scene
  int fmi_version = 2;      // 2 or 3
  std::string output;       // the .fmu to write
  std::string binary;       // the mechsim_fmu shared object to pack
};

// The participant's configuration from a loaded scene; refuses (std::invalid_argument,
// naming the scene file and key) an unknown participant, a type that is not the
// participant's and a participant played by an FMU.
ExportConfig export_config(const config::Scene& scene, const ExportRequest& request);

// modelDescription.xml of the participant for FMI 2.0 or 3.0, with `model_identifier`.
std::string model_description_xml(const ExportedParticipant& participant, int fmi_version,
                                   const std::string& model_identifier, const std::string& token);

// A C identifier from the participant's name (the binary's file name in the archive).
std::string model_identifier(const std::string& participant);

// Writes the FMU; throws std::runtime_error naming the file on any I/O failure.
void write_fmu(const ExportConfig& config, const ExportRequest& request);

// Where the prebuilt FMU binary lies: next to the running executable (the build's bin/ or
// an installation's), or `$MECHSIM_FMU_BINARY`. Empty when none is found.
std::string default_fmu_binary();

}  // namespace mechsim::fmi_export
