// Compiled by the glm_configuration_check test with GLM configured against collide's layout (the
// macros come from the command line): collide's headers must refuse it with their message.
#include <collide/collide.h>

int main() { return 0; }
