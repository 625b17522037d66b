/* gb_export — GB_API marks the library's public functions: the only symbols libgomboc.so exports (the
 * library is compiled with -fvisibility=hidden; `make verify` compares `nm -D` with the declarations that
 * carry the mark). Internal functions, shared between the library's own files, stay inside it. */
#ifndef GB_EXPORT_H
#define GB_EXPORT_H

#if defined(__GNUC__) || defined(__clang__)
#define GB_API __attribute__((visibility("default")))
#else
#define GB_API
#endif

#endif
