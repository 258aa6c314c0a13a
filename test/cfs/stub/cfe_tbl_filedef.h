/* Stand-in for cFE's cfe_tbl_filedef.h, so that the Kestrel tests compile
 * KESTREL_ACS's default table source without cFS: the file definition that
 * elf2cfetbl reads is not needed here. */
#ifndef KESTREL_TEST_CFE_TBL_FILEDEF_H
#define KESTREL_TEST_CFE_TBL_FILEDEF_H
#define CFE_TBL_FILEDEF(obj, name, desc, file)
#endif
