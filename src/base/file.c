/* Reading a whole file into memory. */
#include "base/file.h"

#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

unsigned char* tb_file_read(const char* path, size_t max_bytes, size_t* size)
{
    FILE* f = path ? fopen(path, "rb") : NULL;
    if (!f) return NULL;
    struct stat st;
    unsigned char* data = NULL;
    if (fstat(fileno(f), &st) == 0 && S_ISREG(st.st_mode) && st.st_size >= 0 &&
        (unsigned long long)st.st_size <= max_bytes && (data = malloc((size_t)st.st_size + 1))) {
        size_t n = fread(data, 1, (size_t)st.st_size, f);
        if (n == (size_t)st.st_size && fgetc(f) == EOF) {
            data[n] = 0;
            *size = n;
        } else {
            free(data);
            data = NULL;
        }
    }
    fclose(f);
    return data;
}
