// The parameters of the optional Earth-rate removal (earth_rate.h), named alike by every procedure
// spec that offers it (bias, turn-on time): remove_earth_rate (the flag --remove-earth-rate; true or
// false in a plan), latitude_deg and heading_deg (--latitude, --heading; in a plan [site]'s) and
// ira_elevation_deg (--elevation; the plan key ira_elevation_deg, only with remove_earth_rate).
#pragma once

#include <limits>
#include <optional>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"
#include "inertest/procedures/earth_rate.h"

namespace inertest {

// Declares the four parameters on `definition`, storing the orientation in `axis` when
// remove_earth_rate is true. A latitude, heading or elevation given without it is an Error (the
// command line's --latitude alone was ignored: the bias kept the Earth rate unsaid); a plan's [site]
// gives the latitude and heading only to a step that removes it. The latitude has no default: not
// given, it stays NaN and the orientation's validate() asks for it (0 assumed unsaid removed the
// equator's Earth rate). The heading is north and the elevation horizontal unless given.
template <typename Options, typename Result>
ProcedureDefinition<Options, Result>& earth_rate_parameters(ProcedureDefinition<Options, Result>& definition,
                                                             std::optional<AxisOrientation> Options::*axis) {
  // An angle of the orientation, only with remove_earth_rate.
  const auto orientation_angle = [&definition, axis](ParameterSpec parameter, double AxisOrientation::*angle) {
    const std::string used_only = parameter.name + " (" + parameter.command_line_option() +
                                  ") is used only with remove_earth_rate (--remove-earth-rate)";
    definition.parameter(std::move(parameter), [axis, angle, used_only](Options& options, const nlohmann::json& value) {
      if (!(options.*axis)) throw Error(used_only);
      (*(options.*axis)).*angle = value.get<double>();
    });
  };
  const auto removes_earth_rate = [](const ProcedureCall& call, const nlohmann::json&) {
    return call.parameters.value("remove_earth_rate", false);
  };
  definition.parameter(
      ParameterSpec("remove_earth_rate", "remove the Earth rate along the IRA (site latitude, IRA heading and elevation)")
          .boolean(),
      false, [axis](Options& options, const nlohmann::json& value) {
        if (value.get<bool>()) options.*axis = AxisOrientation{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
      });
  orientation_angle(ParameterSpec("latitude_deg", "site latitude (north positive; needed with remove_earth_rate)")
                        .unit_is("deg")
                        .site_gives("latitude_deg", true)
                        .instrument_gives_if(removes_earth_rate)
                        .command_line_name_is("latitude"),
                    &AxisOrientation::latitude_deg);
  orientation_angle(ParameterSpec("heading_deg", "azimuth of the IRA from north (east positive; default 0)")
                        .unit_is("deg")
                        .site_gives("heading_deg", true)
                        .instrument_gives_if(removes_earth_rate)
                        .command_line_name_is("heading"),
                    &AxisOrientation::heading_deg);
  orientation_angle(ParameterSpec("ira_elevation_deg", "elevation of the IRA above the horizontal (default 0)")
                        .unit_is("deg")
                        .command_line_name_is("elevation"),
                    &AxisOrientation::elevation_deg);
  return definition;
}

}  // namespace inertest
