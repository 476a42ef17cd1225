/* The blast plugin's parameter block (tools/plugins/blast.c), shared by blast.comp. */
#ifndef TB_BLAST_H
#define TB_BLAST_H

#include "layout.h"

TB_STRUCT(tb_blast_params) {
    TB_VEC4 centre;      /* xyz centre (m, world), w strength: m/s^2 at the centre, falling
                            linearly to 0 at the radius; < 0 pulls */
    TB_VEC4 reach;       /* x radius (m, > 0), y z w unused */
};

#endif
