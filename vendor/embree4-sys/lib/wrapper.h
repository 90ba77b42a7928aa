#include "embree4/rtcore.h"
