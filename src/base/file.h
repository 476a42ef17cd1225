/* Reading a whole file into memory. */
#ifndef TB_BASE_FILE_H
#define TB_BASE_FILE_H

#include <stddef.h>

/// The bytes of the regular file at `path` with a 0 after them (malloc'd; *size excludes
/// the 0), or NULL when it cannot be opened, is not a regular file (a directory opens for
/// reading and reports an end far past any real size), is larger than `max_bytes` or
/// cannot be read whole.
unsigned char* tb_file_read(const char* path, size_t max_bytes, size_t* size);

#endif
