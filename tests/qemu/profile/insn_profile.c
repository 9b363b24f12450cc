/* QEMU TCG plugin (API v1, QEMU 7.2): executed-instruction count per guest
 * address, for a flat profile of a firmware (profile.sh maps the addresses to
 * functions and source lines).
 * Args: out=<file> (written at exit as "<hex address> <count>" lines).
 * Addresses below 4 MiB (the mps2 boards' code memory) only; single vCPU.
 * Build: gcc -O2 -shared -fPIC -fvisibility=hidden -o libinsn_profile.so insn_profile.c */
#include <stdint.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The few QEMU 7.2 plugin API (version 1) prototypes used; Debian ships no header. */
typedef uint64_t qemu_plugin_id_t;
struct qemu_plugin_tb;
struct qemu_plugin_insn;
typedef struct { const char *target_name; struct { int min, cur; } version; bool system_emulation;
                 union { struct { int smp_vcpus, max_vcpus; } system; }; } qemu_info_t;
enum qemu_plugin_op { QEMU_PLUGIN_INLINE_ADD_U64 };
typedef void (*tb_trans_cb)(qemu_plugin_id_t, struct qemu_plugin_tb *);
typedef void (*udata_cb)(qemu_plugin_id_t, void *);
void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t, tb_trans_cb);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t, udata_cb, void *);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *, size_t);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *, enum qemu_plugin_op, void *, uint64_t);

__attribute__((visibility("default"))) int qemu_plugin_version = 1;

/* Thumb instructions are 2-byte aligned: one counter per half-word. */
#define CODE_BYTES (4u << 20)
static uint64_t *counts;
static uint64_t outside;
static const char *out_path = "insn-profile.txt";

static void tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb) {
    (void)id;
    size_t n = qemu_plugin_tb_n_insns(tb);
    for (size_t i = 0; i < n; i++) {
        struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
        uint64_t pc = qemu_plugin_insn_vaddr(insn);
        uint64_t *slot = pc < CODE_BYTES ? &counts[pc / 2] : &outside;
        qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, slot, 1);
    }
}

static void at_exit(qemu_plugin_id_t id, void *u) {
    (void)id; (void)u;
    FILE *f = fopen(out_path, "w");
    if (!f) { perror(out_path); return; }
    for (uint64_t i = 0; i < CODE_BYTES / 2; i++)
        if (counts[i]) fprintf(f, "%llx %llu\n", (unsigned long long)(i * 2), (unsigned long long)counts[i]);
    if (outside) fprintf(f, "outside %llu\n", (unsigned long long)outside);
    fclose(f);
}

__attribute__((visibility("default")))
int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info, int argc, char **argv) {
    (void)info;
    for (int i = 0; i < argc; i++) {
        if (!strncmp(argv[i], "out=", 4)) out_path = argv[i] + 4;
        else { fprintf(stderr, "insn_profile: unknown arg %s\n", argv[i]); return -1; }
    }
    counts = calloc(CODE_BYTES / 2, sizeof *counts);
    if (!counts) return -1;
    qemu_plugin_register_vcpu_tb_trans_cb(id, tb_trans);
    qemu_plugin_register_atexit_cb(id, at_exit, NULL);
    return 0;
}
