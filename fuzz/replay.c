/* The fuzz target without libFuzzer: every file named, or every file in
 * a folder named, goes once through LLVMFuzzerTestOneInput
 * (fuzz_scene.c), as libFuzzer would replay a corpus.  ctest runs it on
 * fuzz/corpus in every build, the sanitizer build included, so that an
 * input that once crashed the parser keeps being tried without clang.
 * A crash or a sanitizer report fails the test; a refused scene is an
 * ordinary outcome.  Exit status 0 after at least one input, 1 when a
 * path cannot be read or no input was found.
 *
 *   fuzz_replay fuzz/corpus [FILE...]
 */
#define _POSIX_C_SOURCE 200809L

#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* One file through the target; 0, or 1 if it cannot be read. */
static int replay_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "fuzz_replay: cannot open %s\n", path);
    return 1;
  }
  size_t cap = 4096, n = 0;
  uint8_t *buf = malloc(cap);
  int st = buf == NULL;
  while (!st) {
    n += fread(buf + n, 1, cap - n, f);
    if (n < cap) break;
    uint8_t *b = realloc(buf, 2 * cap);
    if (!b) st = 1;
    else buf = b, cap *= 2;
  }
  if (!st && ferror(f)) st = 1;
  fclose(f);
  if (st) fprintf(stderr, "fuzz_replay: cannot read %s\n", path);
  else LLVMFuzzerTestOneInput(buf, n);
  free(buf);
  return st;
}

int main(int argc, char **argv) {
  long count = 0;
  int bad = 0;
  for (int i = 1; i < argc; i++) {
    struct stat sb;
    if (stat(argv[i], &sb) != 0) {
      fprintf(stderr, "fuzz_replay: no such file or folder: %s\n", argv[i]);
      bad = 1;
      continue;
    }
    if (!S_ISDIR(sb.st_mode)) {
      bad |= replay_file(argv[i]);
      count++;
      continue;
    }
    DIR *d = opendir(argv[i]);
    if (!d) {
      fprintf(stderr, "fuzz_replay: cannot open folder %s\n", argv[i]);
      bad = 1;
      continue;
    }
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
      if (e->d_name[0] == '.') continue;
      size_t len = strlen(argv[i]) + strlen(e->d_name) + 2;
      char *path = malloc(len);
      if (!path) {
        bad = 1;
        break;
      }
      snprintf(path, len, "%s/%s", argv[i], e->d_name);
      if (stat(path, &sb) == 0 && S_ISREG(sb.st_mode)) {
        bad |= replay_file(path);
        count++;
      }
      free(path);
    }
    closedir(d);
  }
  printf("fuzz_replay: %ld inputs replayed\n", count);
  if (count == 0) fprintf(stderr, "fuzz_replay: no input found\n");
  return bad || count == 0;
}
