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
// remove_earth_rate is true; an elevation without it is an Error. The latitude has no default: not
// given, it stays NaN and the orientation's validate() asks for it (0 assumed unsaid removed the
// equator's Earth rate). The heading defaults to north, the elevation to horizontal.
template <typename Options, typename Result>
ProcedureDefinition<Options, Result>& earth_rate_parameters(ProcedureDefinition<Options, Result>& definition,
                                                             std::optional<AxisOrientation> Options::*axis) {
  // An angle of the orientation, set only with remove_earth_rate: [site]'s `name` in a plan.
  const auto site_angle = [&definition, axis](const char* name, const char* doc, const char* option,
                                              double AxisOrientation::*angle, std::optional<double> default_value) {
    ParameterSpec parameter = ParameterSpec(name, doc).unit_is("deg").site_gives(name, true).command_line_name_is(option);
    const auto bind = [axis, angle](Options& options, const nlohmann::json& value) {
      if (options.*axis) (*(options.*axis)).*angle = value.get<double>();
    };
    if (default_value) {
      definition.parameter(std::move(parameter), *default_value, bind);
    } else {
      definition.parameter(std::move(parameter), bind);
    }
  };
  definition.parameter(
      ParameterSpec("remove_earth_rate", "remove the Earth rate along the IRA (site latitude, IRA heading and elevation)")
          .boolean(),
      false, [axis](Options& options, const nlohmann::json& value) {
        if (value.get<bool>()) options.*axis = AxisOrientation{std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0};
      });
  site_angle("latitude_deg", "site latitude (north positive; needed with remove_earth_rate)", "latitude",
             &AxisOrientation::latitude_deg, std::nullopt);
  site_angle("heading_deg", "azimuth of the IRA from north (east positive)", "heading", &AxisOrientation::heading_deg,
             0.0);
  return definition.parameter(
      ParameterSpec("ira_elevation_deg", "elevation of the IRA above the horizontal (default 0)")
          .unit_is("deg")
          .command_line_name_is("elevation"),
      [axis](Options& options, const nlohmann::json& value) {
        if (!(options.*axis)) throw Error("ira_elevation_deg (--elevation) is used only with remove_earth_rate");
        (options.*axis)->elevation_deg = value.get<double>();
      });
}

}  // namespace inertest
