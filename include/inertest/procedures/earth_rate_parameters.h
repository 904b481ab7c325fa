// The parameters of the optional Earth-rate removal (earth_rate.h), named alike by every procedure
// spec that offers it (bias, turn-on time): remove_earth_rate (the flag --remove-earth-rate; true or
// false in a plan), latitude_deg and heading_deg (--latitude, --heading; in a plan [site]'s) and
// ira_elevation_deg (--elevation; the plan key ira_elevation_deg, only with remove_earth_rate).
#pragma once

#include <optional>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/earth_rate.h"

namespace inertest {

// Declares the four parameters on `definition`, storing the orientation in `axis` when
// remove_earth_rate is true; an elevation without it is an Error.
template <typename Options, typename Result>
ProcedureDefinition<Options, Result>& earth_rate_parameters(ProcedureDefinition<Options, Result>& definition,
                                                             std::optional<AxisOrientation> Options::*axis) {
  return definition
      .parameter(ParameterSpec("remove_earth_rate", "remove the Earth rate along the IRA (site latitude, IRA heading and "
                                                    "elevation)")
                     .boolean(),
                 false,
                 [axis](Options& options, const nlohmann::json& value) {
                   if (value.get<bool>()) options.*axis = AxisOrientation{};
                 })
      .parameter(ParameterSpec("latitude_deg", "site latitude (north positive)")
                     .unit_is("deg")
                     .site_gives("latitude_deg")
                     .command_line_name_is("latitude"),
                 0.0,
                 [axis](Options& options, const nlohmann::json& value) {
                   if (options.*axis) (options.*axis)->latitude_deg = value.get<double>();
                 })
      .parameter(ParameterSpec("heading_deg", "azimuth of the IRA from north (east positive)")
                     .unit_is("deg")
                     .site_gives("heading_deg")
                     .command_line_name_is("heading"),
                 0.0,
                 [axis](Options& options, const nlohmann::json& value) {
                   if (options.*axis) (options.*axis)->heading_deg = value.get<double>();
                 })
      .parameter(ParameterSpec("ira_elevation_deg", "elevation of the IRA above the horizontal (default 0)")
                     .unit_is("deg")
                     .command_line_name_is("elevation"),
                 [axis](Options& options, const nlohmann::json& value) {
                   if (!(options.*axis)) throw Error("ira_elevation_deg (--elevation) is used only with remove_earth_rate");
                   (options.*axis)->elevation_deg = value.get<double>();
                 });
}

}  // namespace inertest
