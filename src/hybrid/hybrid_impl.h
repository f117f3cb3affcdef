/* Private to the hybrid layer and the models built on it. */
#ifndef SC_HYBRID_IMPL_H
#define SC_HYBRID_IMPL_H

/* C11 has no M_PI. */
#define SC_PI 3.14159265358979323846

#endif
