// The warm-up time procedure (GJB 2426A-2004 5.6, computed as 5.5.4): declared with turn-on time by
// power_on_time_spec (turn_on_time_spec.cc).
#include "inertest/procedures/turn_on_time.h"

namespace inertest {

ProcedureSpec warm_up_time_spec() { return power_on_time_spec(true); }

}  // namespace inertest
