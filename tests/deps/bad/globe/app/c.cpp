#include "plugin/landsea/LandSea.h"
#include "plugin/ocean/Ocean.h"
