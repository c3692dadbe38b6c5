#include "globe/render/GlobeRenderer.h"
