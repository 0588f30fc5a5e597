/* JSON text for the exporters: a jansson tree printed with numbers in their
 * shortest form that reads back to the same double (0.3, not
 * 0.29999999999999999), arrays of numbers on one line, strings escaped by
 * jansson. */
#ifndef SE_JSONTEXT_H
#define SE_JSONTEXT_H

#include <jansson.h>

#include "se_buf.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Appends `value` as JSON text. `indent` > 0 pretty-prints with that many
 * spaces per level; 0 writes it on one line. */
void se_json_text(se_buf *b, const json_t *value, int indent);

/* Appends the shortest decimal form of v that strtod reads back exactly. */
void se_json_number(se_buf *b, double v);

#ifdef __cplusplus
}
#endif
#endif
