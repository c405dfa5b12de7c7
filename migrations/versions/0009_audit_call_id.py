"""audit rows written before their call's command is sent carry the call's id, to finish them by it

Revision ID: 0009
Revises: 0008
Create Date: 2026-11-29

"""
from typing import Sequence, Union

from alembic import op
import sqlalchemy as sa


# revision identifiers, used by Alembic.
revision: str = '0009'
down_revision: Union[str, Sequence[str], None] = '0008'
branch_labels: Union[str, Sequence[str], None] = None
depends_on: Union[str, Sequence[str], None] = None


def upgrade() -> None:
    """Upgrade schema."""
    with op.batch_alter_table('audit', schema=None) as batch_op:
        batch_op.add_column(sa.Column('call_id', sa.String(length=32), nullable=True))
        batch_op.create_index(batch_op.f('ix_audit_call_id'), ['call_id'], unique=True)


def downgrade() -> None:
    """Downgrade schema."""
    with op.batch_alter_table('audit', schema=None) as batch_op:
        batch_op.drop_index(batch_op.f('ix_audit_call_id'))
        batch_op.drop_column('call_id')
