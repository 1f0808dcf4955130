#include "base/types.h"

#include <sstream>

namespace gearkit
{
void
require_value(bool ok, const std::string &context, const std::string &parameter, double value,
              const std::string &allowed)
{
  if (ok)
    return;
  std::ostringstream msg;
  msg << context << ": " << parameter << " = " << value << " is not allowed; expected " << allowed;
  throw InputError(msg.str());
}
} // namespace gearkit
