// The floor for any OpenImageIO-linked process: start, touch the library, exit.
#include <OpenImageIO/imageio.h>
int main() { return OIIO::openimageio_version() > 0 ? 0 : 1; }
