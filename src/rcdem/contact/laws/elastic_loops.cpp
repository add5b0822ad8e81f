// Elastic's loops over contacts, compiled here alone (contact/law_loops.hpp says why).
#include "rcdem/contact/law_loops.hpp"

namespace rcdem {
RCDEM_LAW_LOOPS(, Elastic);
}  // namespace rcdem
