/* Files watched for changes (inotify), for shader hot-reload: the directories of the files
 * a shader was compiled from are watched, and a poll between steps says which files were
 * written since the last one. */
#ifndef TB_WATCH_H
#define TB_WATCH_H

#include <stdint.h>

typedef struct tb_watched_dir {
    int wd;
    char* path;        ///< canonical
} tb_watched_dir;

typedef struct tb_watch {
    int fd;            ///< the inotify instance; -1 while closed
    tb_watched_dir* dirs;
    uint32_t dir_count;
} tb_watch;

/// Start watching nothing yet; 0 when the system has no inotify instance to give.
int tb_watch_open(tb_watch* watch);
void tb_watch_close(tb_watch* watch);
/// Watch the directory holding the canonical path `file` (once). 0 on failure.
int tb_watch_add_file(tb_watch* watch, const char* file);

/// Called with each file written or moved into a watched directory since the last poll
/// (a canonical path); `file` NULL: events were lost, consider everything changed.
typedef void tb_watch_fn(void* user, const char* file);
/// Report what changed, without blocking; returns how many reports were made.
uint32_t tb_watch_poll(tb_watch* watch, tb_watch_fn* fn, void* user);

#endif
