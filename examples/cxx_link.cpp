// A C++ program using libgomboc through its C interface (the headers' extern "C" guards): the mass
// properties of Gömböc I (β = 0.12) and its contact for one vertical. Build:
//   c++ cxx_link.cpp $(pkg-config --cflags --libs gomboc)
#include <gomboc.h>

#include <cstdio>

int main()
{
    gb_error_init_gsl();
    gb_surface body;
    if (gb_surface_init(&body, "I", 0.12) != GB_OK) {
        std::fprintf(stderr, "surface: %s\n", gb_error_message());
        return 1;
    }
    gb_massprops props;
    const gb_massprops_def def = gb_massprops_default_def();
    if (gb_massprops_compute(&body, &def, &props) != GB_OK) {
        std::fprintf(stderr, "massprops: %s\n", gb_error_message());
        return 1;
    }
    std::printf("C++ against libgomboc: Gomboc I, beta 0.12: volume %.12f, L %.12f\n", props.volume, props.L);
    return 0;
}
