"""cluster: nodes, vehicle leases, pinning a vehicle to nodes by tag

Revision ID: 0003
Revises: 0002
Create Date: 2026-11-24

"""
from typing import Sequence, Union

from alembic import op
import sqlalchemy as sa


# revision identifiers, used by Alembic.
revision: str = '0003'
down_revision: Union[str, Sequence[str], None] = '0002'
branch_labels: Union[str, Sequence[str], None] = None
depends_on: Union[str, Sequence[str], None] = None


def upgrade() -> None:
    """Upgrade schema."""
    op.create_table('cluster_nodes',
    sa.Column('node_id', sa.String(length=32), nullable=False),
    sa.Column('tags', sa.JSON(), nullable=False),
    sa.Column('api_url', sa.String(length=256), nullable=True),
    sa.Column('started_at', sa.DateTime(timezone=True), nullable=False),
    sa.Column('last_seen', sa.DateTime(timezone=True), nullable=False),
    sa.Column('expires_at', sa.DateTime(timezone=True), nullable=False),
    sa.PrimaryKeyConstraint('node_id', name=op.f('pk_cluster_nodes'))
    )
    with op.batch_alter_table('cluster_nodes', schema=None) as batch_op:
        batch_op.create_index(batch_op.f('ix_cluster_nodes_expires_at'), ['expires_at'], unique=False)

    op.create_table('vehicle_leases',
    sa.Column('vehicle_id', sa.String(length=32), nullable=False),
    sa.Column('node_id', sa.String(length=32), nullable=False),
    sa.Column('epoch', sa.BigInteger(), nullable=False),
    sa.Column('acquired_at', sa.DateTime(timezone=True), nullable=False),
    sa.Column('renewed_at', sa.DateTime(timezone=True), nullable=False),
    sa.Column('expires_at', sa.DateTime(timezone=True), nullable=False),
    sa.ForeignKeyConstraint(['vehicle_id'], ['vehicles.id'], name=op.f('fk_vehicle_leases_vehicle_id_vehicles'), ondelete='CASCADE'),
    sa.PrimaryKeyConstraint('vehicle_id', name=op.f('pk_vehicle_leases'))
    )
    with op.batch_alter_table('vehicle_leases', schema=None) as batch_op:
        batch_op.create_index(batch_op.f('ix_vehicle_leases_node_id'), ['node_id'], unique=False)

    with op.batch_alter_table('vehicles', schema=None) as batch_op:
        batch_op.add_column(sa.Column('node_tag', sa.String(length=32), nullable=True))


def downgrade() -> None:
    """Downgrade schema."""
    with op.batch_alter_table('vehicles', schema=None) as batch_op:
        batch_op.drop_column('node_tag')

    with op.batch_alter_table('vehicle_leases', schema=None) as batch_op:
        batch_op.drop_index(batch_op.f('ix_vehicle_leases_node_id'))

    op.drop_table('vehicle_leases')
    with op.batch_alter_table('cluster_nodes', schema=None) as batch_op:
        batch_op.drop_index(batch_op.f('ix_cluster_nodes_expires_at'))

    op.drop_table('cluster_nodes')
