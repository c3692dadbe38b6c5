#include "plugin/waves/WaveField.h"
