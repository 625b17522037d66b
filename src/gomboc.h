/* gomboc.h — the public interface of libgomboc in one include.
 *
 * Every module has its own header (gb_<module>.h, prefix gb_<module>_); this one includes them all. A
 * program that links the library compiles with `pkg-config --cflags gomboc` and links with
 * `pkg-config --libs gomboc` (see README: "The library"). Functions return a gb_ status (0 on
 * success) and leave a message in gb_error_message(); the library never prints and never exits. Call
 * gb_error_init_gsl() once before using a module that calls GSL. */
#ifndef GOMBOC_H
#define GOMBOC_H

#include "gb_error.h"
#include "gb_file.h"
#include "gb_parse.h"
#include "gb_surface.h"
#include "gb_massprops.h"
#include "gb_mesh.h"
#include "gb_polyhedron.h"
#include "gb_body.h"
#include "gb_shape.h"
#include "gb_contact.h"
#include "gb_certify.h"
#include "gb_atlas.h"
#include "gb_forcing.h"
#include "gb_dynamics.h"
#include "gb_impact.h"
#include "gb_integrate.h"
#include "gb_nondim.h"
#include "gb_strobe.h"
#include "gb_spectrum.h"
#include "gb_lyapunov.h"
#include "gb_lyapunov_body.h"
#include "gb_case.h"
#include "gb_run.h"
#include "gb_scan.h"
#include "gb_melnikov.h"
#include "gb_melnikov_body.h"
#include "gb_proof.h"
#include "gb_proof_body.h"
#include "gb_handle.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifdef __cplusplus
}
#endif

#endif
