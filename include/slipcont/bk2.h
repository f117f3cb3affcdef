/**
 * @file bk2.h
 * @brief What is particular to the two-block Burridge-Knopoff model
 *        (sc_model_bk2, models.h; docs/model.md): the numbering of its
 *        modes in trajectory samples and its switching point d*.  The
 *        rest of the library knows it through the model interface only.
 */
#ifndef SLIPCONT_BK2_H
#define SLIPCONT_BK2_H

#include "slipcont/common.h"

#ifdef __cplusplus
extern "C" {
#endif

/** bk2 modes (docs/model.md): the `mode` of trajectory samples. */
enum {
  SC_BK2_STICK = 0,  /**< both blocks stuck: global stick phase */
  SC_BK2_SLIP1 = 1,  /**< block 1 slips, block 2 stuck */
  SC_BK2_SLIP2 = 2,  /**< block 2 slips, block 1 stuck */
  SC_BK2_SLIP12 = 3, /**< both slip */
};

/** d* = (beta - 1)/(1 + 2 alpha): below it block 1 reaches its
 * threshold first (docs/model.md). */
SC_API double sc_bk2_dstar(double alpha, double beta);

#ifdef __cplusplus
}
#endif
#endif
