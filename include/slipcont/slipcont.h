/**
 * @file slipcont.h
 * @brief The whole public API of slipcont: include this one header.
 *
 * Everything but io.h is implemented by libslipcont (the numerics: GSL,
 * LAPACK, KLU, OpenMP); io.h (scenes, output files, plots) by
 * libslipcont_io, which adds inih.  A program that calls no function of
 * io.h links libslipcont alone (pkg-config slipcont, CMake
 * slipcont::slipcont); one that does links slipcont_io too (pkg-config
 * slipcont-io, CMake slipcont::slipcont_io).
 */
#ifndef SLIPCONT_SLIPCONT_H
#define SLIPCONT_SLIPCONT_H

#include "slipcont/common.h"
#include "slipcont/linalg.h"
#include "slipcont/continuation.h"
#include "slipcont/curve_system.h"
#include "slipcont/normal_form.h"
#include "slipcont/mapn_system.h"
#include "slipcont/hybrid.h"
#include "slipcont/models.h"
#include "slipcont/bk2.h"
#include "slipcont/map.h"
#include "slipcont/shooting.h"
#include "slipcont/orbits.h"
#include "slipcont/branchn.h"
#include "slipcont/analysis.h"
#include "slipcont/period.h"
#include "slipcont/chart.h"
#include "slipcont/curve.h"
#include "slipcont/io.h"

#endif
