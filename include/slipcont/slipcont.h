/**
 * @file slipcont.h
 * @brief The whole public API of slipcont: include this one header.
 */
#ifndef SLIPCONT_SLIPCONT_H
#define SLIPCONT_SLIPCONT_H

#include "slipcont/common.h"
#include "slipcont/linalg.h"
#include "slipcont/continuation.h"
#include "slipcont/hybrid.h"
#include "slipcont/models.h"
#include "slipcont/map.h"
#include "slipcont/shooting.h"
#include "slipcont/branch.h"
#include "slipcont/analysis.h"
#include "slipcont/chart.h"
#include "slipcont/curve.h"
#include "slipcont/io.h"

#endif
